// Errors: InputError is bad input (a file, a key, a value) that the user can
// fix; front ends print it on one line and exit with status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace relight {

class InputError : public std::runtime_error {
 public:
  // file: the file at fault; where: a JSON pointer, line or other place in it
  // (may be empty); what: what is wrong and what was expected.
  InputError(std::string file, std::string where, const std::string& what)
      : std::runtime_error(compose(file, where, what)), file_(std::move(file)), where_(std::move(where)),
        message_(what) {}

  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }
  // What is wrong, without the file and the place.
  const std::string& message() const { return message_; }

 private:
  static std::string compose(const std::string& file, const std::string& where, const std::string& what) {
    std::string s = file;
    if (!where.empty()) s += ": " + where;
    return s + ": " + what;
  }
  std::string file_, where_, message_;
};

// Thrown when the user cancels long work (Ctrl-C, a cancel button).
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

}  // namespace relight
