#pragma once
// The one error type for a bad scenario spec. Every door (CLI exit code 2, HTTP 400) reports it
// the same way: the dotted path of the field, the offending value and what is allowed.
#include <stdexcept>
#include <string>

namespace rupture {

class SpecError : public std::invalid_argument {
public:
  SpecError(std::string field, std::string value, std::string allowed)
      : std::invalid_argument(compose(field, value, allowed)),
        m_field(std::move(field)), m_value(std::move(value)), m_allowed(std::move(allowed)) {}

  const std::string& field() const { return m_field; }
  const std::string& value() const { return m_value; }
  const std::string& allowed() const { return m_allowed; }

private:
  static std::string compose(const std::string& field, const std::string& value,
                             const std::string& allowed) {
    return "invalid spec: field '" + field + "' = " + value + "; allowed: " + allowed;
  }
  std::string m_field, m_value, m_allowed;
};

}  // namespace rupture
