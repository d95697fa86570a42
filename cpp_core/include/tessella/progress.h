// Progress and cancellation of long operations. A host installs a sink for the
// current thread (ProgressScope); core loops call report_progress(), which
// forwards at most every 50 ms and throws Cancelled when the sink says stop.
// No method signature carries it, so every method can report without change.
#pragma once

#include <functional>
#include <stdexcept>

namespace tessella {

// The user cancelled; nothing the operation built is returned.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled by the user") {}
};

// fraction in [0,1] of the named stage; return false to cancel.
using ProgressSink = std::function<bool(double fraction, const char* stage)>;

class ProgressScope {
 public:
  explicit ProgressScope(ProgressSink sink);
  ~ProgressScope();
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  ProgressSink previous_;
};

// Cheap when no sink is installed or the last report was under 50 ms ago.
void report_progress(double fraction, const char* stage);

// Forwards at once (no 50 ms wait): the pipeline calls it between stages, so
// cancel works for every method, however short its own loops are.
void report_stage(double fraction, const char* stage);

}  // namespace tessella
