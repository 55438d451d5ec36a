"""Run once in the game's embedded interpreter, before any lesson.

`install(package_init)` installs the game's own `lightcone` package (the
embedded extension module plus the wheel's `__init__.py`, whose source the
host passes in), so a lesson never imports a different installed wheel, and
tees `sys.stdout` so that what a lesson prints also reaches the lesson
panel.
"""

import sys
import types


# Most characters `_Printed` keeps for the panel between two drains (the
# panel shows the last 40 lines): a lesson that prints gigabytes in one
# hook does not fill its process's memory.
_KEEP = 1 << 20


class _Printed:
    """`sys.stdout` for lessons: writes through, and keeps the newest
    lines (at most `_KEEP` characters)."""

    def __init__(self, out):
        self.out, self.lines, self._kept = out, [], 0

    def write(self, s):
        if self.out is not None:
            self.out.write(s)
        if self._kept > _KEEP:
            # Drop the oldest half (the host replaces `lines` when it drains).
            half = len(self.lines) // 2 or 1
            del self.lines[:half]
            self._kept = sum(len(x) for x in self.lines)
        self.lines.append(s[-_KEEP:])
        self._kept += min(len(s), _KEEP)
        return len(s)

    def flush(self):
        if self.out is not None:
            self.out.flush()


def _module(name, source):
    module = types.ModuleType(name)
    module.__package__ = "lightcone"
    module.__file__ = f"<lightcone game>/{name.replace('.', '/')}.py"
    sys.modules[name] = module
    exec(compile(source, module.__file__, "exec"), module.__dict__)
    return module


def install(package_init, records):
    """Makes `import lightcone` the game's own module: `package_init` and
    `records` are the sources of the wheel's `__init__.py` and
    `records.py`."""
    import lightcone_embedded

    sys.modules["lightcone._lightcone"] = lightcone_embedded
    pkg = types.ModuleType("lightcone")
    pkg.__path__ = []
    pkg.__package__ = "lightcone"
    pkg.__file__ = "<lightcone game>/lightcone/__init__.py"
    sys.modules["lightcone"] = pkg
    pkg.records = _module("lightcone.records", records)
    exec(compile(package_init, pkg.__file__, "exec"), pkg.__dict__)
    sys.stdout = _Printed(sys.stdout)


def _no_exit(*args, **kwargs):
    raise SystemExit("a lesson cannot end the game (os._exit or os.abort was called)")


def guard(stop):
    """Installs what keeps a misbehaving lesson from ending or hanging the game.

    `stop` raises TimeoutError when the running hook is over its limit (the
    host's watchdog sends SIGUSR2 to break calls that wait, such as
    time.sleep, input() or a socket read). A lesson cannot end the game
    with os._exit / os.abort (the host's audit hook, in Rust, keeps it from
    starting processes or signalling the game).
    """
    import os
    import signal

    try:
        signal.signal(signal.SIGUSR2, stop)
    except ValueError:
        pass  # not the main thread (unit tests): hooks are only timed
    import posix

    for module in (os, posix):
        module._exit = _no_exit
        module.abort = _no_exit
        # A process handle raises no audit event: os.pidfd_open(getppid())
        # and signal.pidfd_send_signal would signal the game past the
        # audit hook. A lesson starts no process, so it needs neither.
        if hasattr(module, "pidfd_open"):
            module.pidfd_open = _no_process_handles
    if hasattr(signal, "pidfd_send_signal"):
        signal.pidfd_send_signal = _no_process_handles
    _catch_thread_errors()


def _no_process_handles(*args, **kwargs):
    raise PermissionError("a lesson may not signal the game's own processes (pidfd)")


# Tracebacks of exceptions that ended threads the lesson started, oldest
# first: the host takes them after each hook and stops the lesson with the
# first (a thread's error would otherwise only be printed, and the lesson
# reported as if nothing had happened).
thread_errors = []
_thread_errors_lock = None


def _catch_thread_errors():
    import threading
    import traceback

    global _thread_errors_lock
    _thread_errors_lock = threading.Lock()

    def caught(args):
        if args.exc_type is SystemExit:
            return  # a thread's sys.exit() ends only that thread
        name = args.thread.name if args.thread is not None else "a thread"
        text = "".join(
            traceback.format_exception(args.exc_type, args.exc_value, args.exc_traceback)
        )
        with _thread_errors_lock:
            thread_errors.append(f"in the lesson's thread {name!r}:\n{text.rstrip()}")

    threading.excepthook = caught


def take_thread_errors():
    """The thread errors caught since the last call (and forgets them)."""
    if _thread_errors_lock is None:
        return []
    with _thread_errors_lock:
        taken = list(thread_errors)
        del thread_errors[:]
    return taken
