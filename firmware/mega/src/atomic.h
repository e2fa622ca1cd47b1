// A section the step interrupt cannot enter: interrupts off on AVR, nothing on the single-threaded host.
#pragma once

#ifdef __AVR__
#include <util/atomic.h>
#define UV_ATOMIC ATOMIC_BLOCK(ATOMIC_RESTORESTATE)
#else
#define UV_ATOMIC if (true)
#endif
