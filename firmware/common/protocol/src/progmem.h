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
// A string literal kept in flash; read it only through the uvP* functions.
#define UV_P(s) PSTR(s)
#define uvStrlenP strlen_P
#define uvMemcpyP memcpy_P
#define uvMemcmpP memcmp_P
#else
#include <string.h>
#define UV_FLASH
#define uvFlashByte(p) (*(reinterpret_cast<const uint8_t*>(p)))
#define uvFlashDword(p) (*(p))
#define uvFlashPtr(p) (p)
#define uvFlashStrncpy strncpy
#define UV_P(s) (s)
#define uvStrlenP strlen
#define uvMemcpyP memcpy
#define uvMemcmpP memcmp
#endif
