// Keyword options -> fields of the libraries' Options structs: a setter per keyword that checks
// the Python value's type before it writes the field (a bool is refused for a number and a
// number for a bool, an int beyond the field's range is a ValueError), and ApplyOptions, which
// sets a dict of keywords through a table of setters and names the unknown ones.
#pragma once

#include <pybind11/pybind11.h>

#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

namespace comic::python {

namespace py = pybind11;

using Setter = std::function<void(py::handle)>;
using OptionTable = std::map<std::string, Setter>;

// A Python int `value` holds a T exactly.
template <typename T>
bool FitsIn(py::handle value) {
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if constexpr (std::is_unsigned_v<T>) {
    if (overflow > 0) {  // above long long: an unsigned long long may still hold it
      const unsigned long long u = PyLong_AsUnsignedLongLong(value.ptr());
      if (PyErr_Occurred()) {
        PyErr_Clear();
        return false;
      }
      return u <= std::numeric_limits<T>::max();
    }
  }
  if (overflow != 0 || (v == -1 && PyErr_Occurred())) {
    PyErr_Clear();
    return false;
  }
  if constexpr (std::is_signed_v<T>) {
    return v >= std::numeric_limits<T>::min() && v <= std::numeric_limits<T>::max();
  } else {
    return v >= 0 && static_cast<unsigned long long>(v) <= std::numeric_limits<T>::max();
  }
}

template <typename T>
Setter Field(T* field) {
  return [field](py::handle value) {
    // A bool is an int to Python: refuse it for numbers, and numbers for a bool, so that a
    // swapped argument is an error rather than a silent 1 or true.
    if constexpr (std::is_same_v<T, bool>) {
      if (!py::isinstance<py::bool_>(value)) throw py::type_error("expects a bool");
    } else if constexpr (std::is_arithmetic_v<T>) {
      if (py::isinstance<py::bool_>(value)) throw py::type_error("expects a number, not a bool");
      // An int beyond the field's range is a bad value, not a wrong type (threads=10**20).
      if constexpr (std::is_integral_v<T>) {
        if (py::isinstance<py::int_>(value) && !FitsIn<T>(value)) {
          throw py::value_error("= " + py::cast<std::string>(py::str(value)) +
                                " is beyond the range of a " + std::to_string(8 * sizeof(T)) +
                                "-bit integer");
        }
      }
    } else if constexpr (std::is_same_v<T, std::string>) {
      // A path or a name: str (os.PathLike is turned into str by comic/__init__.py).
      if (!py::isinstance<py::str>(value)) throw py::type_error("expects a str");
    }
    *field = py::cast<T>(value);
  };
}

template <typename Parse, typename T>
Setter Parsed(T* field, Parse parse) {
  return [field, parse](py::handle value) { *field = parse(py::cast<std::string>(value)); };
}

// A field whose being given matters (sfm::TrackerSettings: a given value wins over the pairing's).
template <typename T>
Setter Given(std::optional<T>* field) {
  return [field](py::handle value) {
    T given{};
    Field (&given)(value);
    *field = given;
  };
}

// A field of an optional struct: the struct is engaged with its defaults first, as the CLI takes
// the whole struct once any of its flags is given (apps/common/tracker_flags.cc).
template <typename S, typename Access>
Setter InOptional(std::optional<S>* holder, Access access) {
  return [holder, access](py::handle value) {
    S given = holder->value_or(S());
    Field (&access(given))(value);
    *holder = given;
  };
}

// A flag that turns a field off (--mask-keeps-nonzero: mask_drops_nonzero = false); the keyword
// is the flag's name, as every other.
Setter Negated(bool* field);

// --write-frames: True for the default folder (`implicit`), a path, or False / "" for none.
Setter WriteFrames(std::string* field, const char* implicit);

// Sets every (name, value) of `options` through `table`; unknown names raise ValueError listing the
// valid ones, values of the wrong type TypeError, both naming `context` and the option.
void ApplyOptions(const py::dict& options, const OptionTable& table, const std::string& context);

// A keyword argument as an option of `context` (a T, an int beyond T's range a ValueError).
template <typename T>
T Argument(const py::object& value, const std::string& name, const std::string& context) {
  T result{};
  py::dict options;
  options[py::str(name)] = value;
  ApplyOptions(options, {{name, Field(&result)}}, context);
  return result;
}

// One entry of an option table (sfm::RunOptionTable, sfm::DetectorOptionTable) as a dict: its
// flag, keyword, value name, help and the default `defaults` holds (the fields are reached
// through accessors that take it by reference), for docstrings and tests.
template <typename Entry, typename Options>
py::dict OptionEntryDict(const Entry& entry, Options& defaults) {
  py::dict d;
  d["flag"] = entry.flag;
  d["keyword"] = entry.keyword;
  d["metavar"] = entry.metavar;
  d["help"] = entry.help;
  d["default"] = std::visit([&](auto field) { return py::cast(field(defaults)); }, entry.field);
  return d;
}

}  // namespace comic::python
