// The exception family in Python (docs/python.md):
//   Error(Exception)
//     InvalidInput(Error, ValueError)       <- C++ InvalidInput
//       TopologyError(InvalidInput)         <- C++ TopologyError
//     ParseError(Error, ValueError)         <- C++ ParseError; .path, .line, .column
//     IoError(Error, OSError)               <- C++ IoError; .path and .filename
//     NumericalError(Error, ArithmeticError) <- C++ NumericalError
// The message is the C++ one, unchanged: the one line the CLI prints, naming the file.

#include <exception>

#include "core/errors.h"
#include "python/bindings.h"

namespace patchwork::python {
namespace {

namespace py = pybind11;

// The classes, made once at import (they live as long as the interpreter: leaked on purpose,
// as Python's own exception types are).
struct ErrorClasses {
  PyObject* error = nullptr;
  PyObject* invalid_input = nullptr;
  PyObject* topology_error = nullptr;
  PyObject* parse_error = nullptr;
  PyObject* io_error = nullptr;
  PyObject* numerical_error = nullptr;
};
ErrorClasses error_classes;

// A new exception class patchwork.<name> with the given bases, added to the module.
PyObject* new_class(py::module_& m, const char* name, const char* doc, py::tuple bases, py::dict members = py::dict()) {
  const std::string qualified = std::string("patchwork.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), members.ptr());
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

// Raises an instance of `type` with `message` and the given attributes.
void raise(PyObject* type, const char* message, py::dict attributes) {
  py::object instance = py::reinterpret_borrow<py::object>(type)(message);
  for (const auto& [key, value] : attributes) py::setattr(instance, key, value);
  PyErr_SetObject(type, instance.ptr());
}

}  // namespace

void bind_errors(py::module_& m) {
  ErrorClasses& c = error_classes;
  const py::handle value_error(PyExc_ValueError);
  c.error = new_class(m, "Error", "Base class of every patchwork error.", py::make_tuple(py::handle(PyExc_Exception)));
  c.invalid_input = new_class(m, "InvalidInput", "The caller's data violates a documented precondition.",
                              py::make_tuple(py::handle(c.error), value_error));
  c.topology_error = new_class(m, "TopologyError", "Mesh connectivity is not what the operation requires.",
                               py::make_tuple(py::handle(c.invalid_input)));
  c.parse_error = new_class(m, "ParseError", "A file's content could not be parsed (path, line, column; 1-based).",
                            py::make_tuple(py::handle(c.error), value_error));
  // OSError's str() would read "[Errno None] None: 'path'" once filename is set: IoError keeps
  // the message as it is, and still sets filename for code written for OSError.
  py::dict io_members;
  io_members["__str__"] = py::module_::import("builtins").attr("BaseException").attr("__str__");
  c.io_error = new_class(m, "IoError", "Reading or writing a file failed (path, and OSError's filename).",
                         py::make_tuple(py::handle(c.error), py::handle(PyExc_OSError)), io_members);
  c.numerical_error = new_class(m, "NumericalError", "A computation cannot deliver its contract.",
                                py::make_tuple(py::handle(c.error), py::handle(PyExc_ArithmeticError)));

  // The most derived C++ types first: TopologyError is an InvalidInput.
  py::register_exception_translator([](std::exception_ptr thrown) {
    const ErrorClasses& k = error_classes;
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const TopologyError& e) {
      raise(k.topology_error, e.what(), py::dict());
    } catch (const InvalidInput& e) {
      raise(k.invalid_input, e.what(), py::dict());
    } catch (const ParseError& e) {
      raise(k.parse_error, e.what(),
            py::dict(py::arg("path") = e.path(), py::arg("line") = e.line(), py::arg("column") = e.column()));
    } catch (const IoError& e) {
      raise(k.io_error, e.what(), py::dict(py::arg("path") = e.path(), py::arg("filename") = e.path()));
    } catch (const NumericalError& e) {
      raise(k.numerical_error, e.what(), py::dict());
    }
  });
}

}  // namespace patchwork::python
