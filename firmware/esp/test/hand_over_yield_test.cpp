// The hand-over on the ESP8266, where the network callbacks also run inside loop()'s step: the
// flash yields while loop() reads the spool (flash_gate.h). Whatever the network does there (a
// second POST, requests handed and answered, a client leaving, a DELETE) keeps the spool loop()'s,
// answers every request once and starts no job that nobody was told of.
#include <gtest/gtest.h>

#include <vector>

#include "hand_over_fakes.h"

using namespace handover;

