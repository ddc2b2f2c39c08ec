#include "interrupt.h"

#include <Python.h>
#include <signal.h>

namespace meshsal_py {
namespace {

// At most one armed call: only the main thread arms one, and it runs one call at a time.
std::atomic<std::atomic<bool>*> armed_flag{nullptr};
struct sigaction python_handler;  // what was installed before ours, restored after the call

void on_sigint(int sig, siginfo_t* info, void* context) {
  if (std::atomic<bool>* f = armed_flag.load()) f->store(true);
  // Python's own handler next: it notes the signal for the interpreter.
  if (python_handler.sa_flags & SA_SIGINFO) {
    if (python_handler.sa_sigaction) python_handler.sa_sigaction(sig, info, context);
  } else if (python_handler.sa_handler == SIG_DFL) {
    signal(SIGINT, SIG_DFL);  // signal.signal(SIGINT, SIG_DFL) was asked for: end the process
    raise(SIGINT);
  } else if (python_handler.sa_handler != SIG_IGN) {
    python_handler.sa_handler(sig);
  }
}

bool on_main_thread() {
  PyObject* threading = PyImport_ImportModule("threading");
  if (!threading) {
    PyErr_Clear();
    return false;
  }
  PyObject* main = PyObject_CallMethod(threading, "main_thread", nullptr);
  PyObject* ident = main ? PyObject_GetAttrString(main, "ident") : nullptr;
  const bool yes = ident && PyLong_AsUnsignedLong(ident) == PyThread_get_thread_ident();
  if (PyErr_Occurred()) PyErr_Clear();
  Py_XDECREF(ident);
  Py_XDECREF(main);
  Py_DECREF(threading);
  return yes;
}

}  // namespace

InterruptibleCall::InterruptibleCall() {
  if (on_main_thread() && sigaction(SIGINT, nullptr, &python_handler) == 0 &&
      python_handler.sa_handler != SIG_IGN) {
    struct sigaction ours {};
    ours.sa_sigaction = on_sigint;
    ours.sa_flags = SA_SIGINFO | SA_ONSTACK;
    sigemptyset(&ours.sa_mask);
    armed_flag.store(&flag_);
    armed_ = sigaction(SIGINT, &ours, nullptr) == 0;
    if (!armed_) armed_flag.store(nullptr);
  }
  saved_thread_state_ = PyEval_SaveThread();
}

InterruptibleCall::~InterruptibleCall() {
  PyEval_RestoreThread(static_cast<PyThreadState*>(saved_thread_state_));
  if (armed_) {
    sigaction(SIGINT, &python_handler, nullptr);
    armed_flag.store(nullptr);
  }
}

void translate_cancelled() {
  if (PyErr_CheckSignals() != 0) return;  // Python's handler raised (KeyboardInterrupt)
  if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
}

}  // namespace meshsal_py
