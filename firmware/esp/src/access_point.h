// Per-device Wi-Fi credentials derived from the chip id: the AP is never open (protocol/esp.md).
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace uv {
namespace esp {

// ssid "UVPrinter-XXXXXX" and a 12-character password from the id; the user can read both on
// the serial log and the Mega's OLED, and change the password in the config.
void accessPointCredentials(uint32_t chipId, char* ssid, size_t ssidSize, char* password, size_t passwordSize);

}  // namespace esp
}  // namespace uv
