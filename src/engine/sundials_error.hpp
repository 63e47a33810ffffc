// camdyn (private) — a failed SUNDIALS call as an exception that says what the flag means
// (src/engine/sundials_flags.cpp), and the check every SUNDIALS call goes through.
#pragma once

#include <stdexcept>
#include <string>

namespace camdyn {

/// What a SUNDIALS return flag of `call` means, in words ("the error test failed
/// repeatedly (…)"); "failed" where the flag carries no meaning (creation failures, and
/// calls whose name explains itself in parentheses).
std::string sundials_flag_words(const std::string& call, int flag);

/// A negative SUNDIALS return flag, turned into an exception naming the call and saying
/// what the flag means (never the bare number).
class SundialsError : public std::runtime_error {
 public:
  SundialsError(const std::string& call, int flag)
      : std::runtime_error(call + ": " + sundials_flag_words(call, flag)), flag_(flag) {}
  int flag() const { return flag_; }

 private:
  int flag_;
};

/// Throws SundialsError if flag < 0. Returns flag otherwise.
inline int check_flag(int flag, const char* call) {
  if (flag < 0) throw SundialsError(call, flag);
  return flag;
}

}  // namespace camdyn
