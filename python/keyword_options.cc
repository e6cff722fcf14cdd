#include "python/keyword_options.h"

#include "io/core/error.h"

namespace comic::python {

Setter Negated(bool* field) {
  return [field](py::handle value) {
    if (!py::isinstance<py::bool_>(value)) throw py::type_error("expects a bool");
    *field = !py::cast<bool>(value);
  };
}

Setter WriteFrames(std::string* field, const char* implicit) {
  return [field, implicit](py::handle value) {
    if (py::isinstance<py::bool_>(value)) {
      *field = py::cast<bool>(value) ? implicit : "";
    } else {
      *field = py::cast<std::string>(value);
    }
  };
}

void ApplyOptions(const py::dict& options, const OptionTable& table, const std::string& context) {
  for (const auto& [key, value] : options) {
    const std::string name = py::cast<std::string>(key);
    const auto it = table.find(name);
    if (it == table.end()) {
      std::string valid;
      for (const auto& entry : table) valid += (valid.empty() ? "" : ", ") + entry.first;
      throw Error(ErrorKind::kInvalidArgument,
                  context + ": unknown option '" + name + "' (valid: " + valid + ")");
    }
    try {
      it->second(value);
    } catch (const py::cast_error&) {
      throw py::type_error(context + ": option '" + name + "' has the wrong type (" +
                           py::cast<std::string>(py::str(value.get_type())) + ")");
    } catch (const py::type_error& e) {
      throw py::type_error(context + ": option '" + name + "' " + e.what());
    } catch (const py::value_error& e) {
      throw Error(ErrorKind::kInvalidArgument, context + ": option '" + name + "' " + e.what());
    }
  }
}

}  // namespace comic::python
