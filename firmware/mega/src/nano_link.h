// The Mega's side of the printhead link: background polls of the Nano and what it last said.
#pragma once
#include <Arduino.h>

#include "line_splitter.h"
#include "nano_codec.h"

class NanoLink {
 public:
  explicit NanoLink(Stream& stream) : stream_(stream), splitter_(line_, uv::kNanoMaxLine) {}

  // Sends the next poll when due and reads replies; never waits.
  void poll(uint32_t nowMs);

  bool online() const { return online_; }
  const int16_t* deciC() const { return deciC_; }

 private:
  void handle(const uv::NanoReply& r);

  Stream& stream_;
  char line_[uv::kNanoMaxLine + 2];
  uv::LineSplitter splitter_;
  int16_t deciC_[uv::kSensorCount] = {};
  uint32_t lastPollMs_ = 0;
  uint32_t lastReplyMs_ = 0;
  uint8_t missed_ = 0;
  bool awaiting_ = false;
  bool online_ = false;
};
