// Mega 2560 + CNC shield pin map: the only place pins are named.
#pragma once

// Serial ports: Serial0 = USB host, Serial1 = printhead Nano, ESP on Serial2 (config may pick Serial3).
#define NANO_SERIAL Serial1
#define ESP_SERIAL_DEFAULT Serial2
