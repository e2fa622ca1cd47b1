// One colour per temperature sensor, shared by the table and the chart.
export const SENSOR_COLOURS = ['#7b2ff7', '#c2185b', '#1565c0', '#00897b', '#ef6c00', '#546e7a'];
