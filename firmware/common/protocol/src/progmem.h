// Constant tables in flash on AVR (PROGMEM) and plain memory on the host, read through one macro.
#pragma once
#include <stdint.h>

#ifdef __AVR__
#include <avr/pgmspace.h>
#define UV_FLASH PROGMEM
#define uvFlashByte(p) pgm_read_byte(p)
#define uvFlashDword(p) static_cast<int32_t>(pgm_read_dword(p))
#define uvFlashPtr(p) reinterpret_cast<const char*>(pgm_read_ptr(&(p)))
#define uvFlashStrncpy strncpy_P
#else
#include <string.h>
#define UV_FLASH
#define uvFlashByte(p) (*(reinterpret_cast<const uint8_t*>(p)))
#define uvFlashDword(p) (*(p))
#define uvFlashPtr(p) (p)
#define uvFlashStrncpy strncpy
#endif
