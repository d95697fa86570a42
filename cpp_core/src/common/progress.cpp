#include "tessella/progress.h"

#include <chrono>

namespace tessella {

namespace {
using Clock = std::chrono::steady_clock;
thread_local ProgressSink current_sink;
thread_local Clock::time_point last_report;
}  // namespace

ProgressScope::ProgressScope(ProgressSink sink) : previous_(std::move(current_sink)) {
  current_sink = std::move(sink);
  last_report = Clock::now();
}

ProgressScope::~ProgressScope() { current_sink = std::move(previous_); }

void report_progress(double fraction, const char* stage) {
  if (!current_sink) return;
  const Clock::time_point now = Clock::now();
  if (now - last_report < std::chrono::milliseconds(50)) return;
  last_report = now;
  if (!current_sink(fraction, stage)) throw Cancelled();
}

void report_stage(double fraction, const char* stage) {
  if (!current_sink) return;
  last_report = Clock::now();
  if (!current_sink(fraction, stage)) throw Cancelled();
}

}  // namespace tessella
