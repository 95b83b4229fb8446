#pragma once
// A request the server refuses: the HTTP status it answers, the kind the lab's status page counts
// it under, and the one line its log gets. Whatever throws one has written nothing.

#include <stdexcept>
#include <string>

namespace countershade::serve {

class Refusal : public std::runtime_error {
 public:
  Refusal(int status, std::string kind, const std::string& message)
      : std::runtime_error(message), status(status), kind(std::move(kind)) {}
  int status;
  std::string kind;
};

}  // namespace countershade::serve
