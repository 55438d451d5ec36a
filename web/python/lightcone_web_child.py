"""A lesson's side in the browser: the Python twin of `child` and
`run_call` in game/src/lesson/remote.rs, run by Pyodide in a Web Worker
(web/static/lesson_worker.js) instead of a process of its own.

The game sends call lines (`{"call": hook, "args": [...], "snapshot":
{...}}`); for each, `Child.run_call` runs the hook on the lesson and
returns the Done line (`{"done": {"error", "timed_out", "printed",
"hooks"}}`, as serde writes remote.rs's `Up::Done`). Inside a hook the
lesson's `World` (`lightcone_remote.World`) sends its requests through
`request`, which the worker makes synchronous for Python: with JSPI it
blocks on the game's answer with `pyodide.ffi.run_sync`, without (Firefox,
Safari) it waits on memory shared with the page (`Atomics.wait`,
lesson_worker.js).

A hook over its time limit gets a `TimeoutError` at its line, as on the
desktop (`game/src/lesson/watchdog.rs`), from `sys.monitoring` (there is
no second thread or signal in a worker): the time is looked at on each
function entry and each backward jump (every loop turns through one),
and once the hook is over its limit `TimeoutError` is raised there and
again at every line of the lesson's code until the hook returns, so an
`except Exception:` in the lesson cannot swallow it (the next is raised
on the handler's own first line). The Done line then says `timed_out`.
What this cannot stop (a long call into C, such as
`sum(range(10**12))`, which never returns to Python) the game stops
`protocol::HOOK_GRACE` later by ending the worker.
"""

import json
import os
import sys
import time
import traceback
import types

import lightcone  # noqa: F401  (the package, loaded before any lesson code)
import lightcone_bootstrap
import lightcone_remote

# The hooks, by the names a call carries (remote.rs's HOOKS).
HOOKS = ("setup", "on_frame", "on_collision", "on_answer")
# How many printed lines a Done message carries, and the longest
# (mod.rs's PRINTED_LINES, remote.rs's `printed_tail`).
PRINTED_LINES = 40
LONGEST = 4096

# Frames of these files are left out of the tracebacks sent to the game:
# the engine's stand-in is native code on the desktop (no frame), and
# this file is Rust there.
_HIDDEN = {os.path.abspath(__file__), os.path.abspath(sys.modules["lightcone._lightcone"].__file__)}
# The code the time limit never interrupts: this file (the game's side of
# the protocol, Rust on the desktop), by the names its code objects carry.
_HIDDEN_CODE = frozenset({__file__, os.path.abspath(__file__)})

_loaded = 0


def lesson_dir(name):
    """The lesson's directory (mod.rs's `lesson_dir`): "." for a bare name."""
    return os.path.dirname(name) or "."


def load_module(name, source):
    """Runs the lesson's `source` as a new module (as mod.rs's
    `load_module`): a name no other load used, `__file__` the lesson's
    `name`, its directory first on `sys.path`; AttributeError if it has
    no `setup`."""
    global _loaded
    if "\0" in source:
        raise SyntaxError("the lesson contains a NUL byte")
    code = compile(source, name, "exec")
    _loaded += 1
    module = types.ModuleType(f"lightcone_lesson_{_loaded}")
    module.__file__ = name
    directory = lesson_dir(name)
    if directory not in sys.path:
        sys.path.insert(0, directory)
    sys.modules[module.__name__] = module
    try:
        exec(code, module.__dict__)
    except BaseException:
        del sys.modules[module.__name__]
        raise
    if not hasattr(module, "setup"):
        raise AttributeError(f"{name}: a lesson needs a function setup(world) that calls world.start(scene)")
    return module


def _hide(te):
    """Drops the hidden files' frames from `te`, its causes and contexts."""
    seen = set()
    todo = [te]
    while todo:
        t = todo.pop()
        if t is None or id(t) in seen:
            continue
        seen.add(id(t))
        t.stack = traceback.StackSummary.from_list(
            [f for f in t.stack if os.path.abspath(f.filename) not in _HIDDEN]
        )
        todo += [t.__cause__, t.__context__] + list(getattr(t, "exceptions", None) or [])


def format_error(e):
    """The traceback of `e` as Python prints it, trimmed (mod.rs's
    `traceback`)."""
    try:
        te = traceback.TracebackException.from_exception(e)
        _hide(te)
        return "".join(te.format()).rstrip()
    except Exception:
        return "".join(traceback.format_exception(e)).rstrip()


def _text(s):
    """`s` as text every JSON reader takes (a lone surrogate replaced)."""
    return s.encode("utf-8", "replace").decode("utf-8")


def drain_printed():
    """What the lesson printed since the last call, as lines (mod.rs's
    `drain_printed`: Rust's `str::lines`), the last PRINTED_LINES, each
    cut to LONGEST characters (remote.rs's `printed_tail`)."""
    out = sys.stdout
    parts = getattr(out, "lines", None)
    if not isinstance(parts, list):
        return []
    out.lines = []
    text = "".join(p for p in parts if isinstance(p, str))
    lines = text.split("\n")
    if lines[-1] == "":
        lines.pop()
    lines = [line[:-1] if line.endswith("\r") else line for line in lines[-PRINTED_LINES:]]
    return [_text(line[:LONGEST] + "…" if len(line) > LONGEST else line) for line in lines]


# The `sys.monitoring` tool id the time limit uses (one of those free for
# tools other than debuggers, coverage and profilers).
_LIMIT_TOOL = 4


class _Limit:
    """A hook's time limit: `TimeoutError` in the lesson's code once
    `seconds` have passed since `start` (module doc)."""

    def __init__(self, seconds, hook, started):
        """`started`: when the call came in (`time.monotonic()`), from
        which the game times the hook too."""
        self.seconds = seconds
        self.hook = hook
        self.started = started
        self.deadline = None
        self.over = False

    def _raise(self):
        raise TimeoutError(
            f"the hook {self.hook} ran longer than its limit of {self.seconds:g} s"
        )

    def _watch(self, code, *_):
        """PY_START and JUMP: the clock, looked at in the lesson's code."""
        if code.co_filename in _HIDDEN_CODE:
            return sys.monitoring.DISABLE
        if self.over or time.monotonic() > self.deadline:
            self._over()
            self._raise()
        return None

    def _line(self, code, _line):
        """LINE, once over: raised again at every line of the lesson's code."""
        if code.co_filename in _HIDDEN_CODE:
            return sys.monitoring.DISABLE
        self._raise()

    def _over(self):
        if not self.over:
            self.over = True
            sys.monitoring.set_events(_LIMIT_TOOL, self._events() | sys.monitoring.events.LINE)

    @staticmethod
    def _events():
        e = sys.monitoring.events
        return e.PY_START | e.JUMP

    def __enter__(self):
        mon = getattr(sys, "monitoring", None)
        if mon is None or not (self.seconds > 0):
            return self
        try:
            mon.use_tool_id(_LIMIT_TOOL, "lightcone hook limit")
        except ValueError:
            mon.free_tool_id(_LIMIT_TOOL)
            mon.use_tool_id(_LIMIT_TOOL, "lightcone hook limit")
        self.deadline = self.started + self.seconds
        mon.register_callback(_LIMIT_TOOL, mon.events.PY_START, self._watch)
        mon.register_callback(_LIMIT_TOOL, mon.events.JUMP, self._watch)
        mon.register_callback(_LIMIT_TOOL, mon.events.LINE, self._line)
        mon.set_events(_LIMIT_TOOL, self._events())
        return self

    def __exit__(self, *exc):
        mon = getattr(sys, "monitoring", None)
        if mon is not None and self.deadline is not None:
            try:
                mon.set_events(_LIMIT_TOOL, 0)
                for event in (mon.events.PY_START, mon.events.JUMP, mon.events.LINE):
                    mon.register_callback(_LIMIT_TOOL, event, None)
                mon.free_tool_id(_LIMIT_TOOL)
            except ValueError:
                pass  # the lesson freed the tool itself: nothing left to undo
        return False


class Child:
    """One lesson in the worker: its source, its `World` stand-in and,
    after `setup`, its module."""

    def __init__(self, name, source, request, limit=0.0):
        """`request(line)` sends a request line to the game and returns its
        answer line (the worker's, blocking); `limit` is the longest a hook
        may run, s (0: no limit here)."""
        self.name = name
        self.source = source
        self.limit = float(limit)
        self.world = lightcone_remote.World(request, lesson_dir(name))
        self.lesson = None

    def _done(self, error, hooks, timed_out=False):
        return json.dumps(
            {
                "done": {
                    "error": None if error is None else _text(error),
                    "timed_out": timed_out,
                    "printed": drain_printed(),
                    "hooks": hooks,
                }
            },
            ensure_ascii=False,
        )

    def run_call(self, line):
        """Runs the call in `line` on the lesson; the Done line."""
        started = time.monotonic()
        try:
            hook, args = lightcone_remote.begin(self.world, line)
            if not isinstance(hook, str):
                raise TypeError(f"the hook's name is a {type(hook).__name__}, not a str")
        except Exception as e:
            return self._done(f"a call the lesson cannot read: {type(e).__qualname__}: {e}", [])
        if hook not in HOOKS:
            return self._done(f"no such hook {json.dumps(hook, ensure_ascii=False)}", [])
        error = None
        limit = _Limit(self.limit, hook, started)
        try:
            with limit:
                if hook == "setup":
                    self.lesson = load_module(self.name, self.source)
                    self.lesson.setup(*args)
                else:
                    f = getattr(self.lesson, hook, None) if self.lesson is not None else None
                    if f is not None:
                        f(*args)
        except BaseException as e:  # as the desktop: SystemExit, KeyboardInterrupt too
            error = format_error(e)
            if hook != "setup":
                error = f"in {hook}:\n{error}"
        hooks = []
        if hook == "setup" and self.lesson is not None:
            hooks = [h for h in HOOKS[1:] if hasattr(self.lesson, h)]
        return self._done(error, hooks, limit.over)


def start(name, source, request, limit=0.0):
    """The worker's entry: tees `sys.stdout` (what the lesson prints goes
    to the browser's console and into the Done message), keeps the lesson
    from ending the interpreter with os._exit / os.abort (as the desktop's
    `lightcone_bootstrap.guard`: a SystemExit saying so), and returns the
    lesson's `Child`, whose hooks stop at `limit` s (module doc)."""
    import posix

    if not isinstance(sys.stdout, lightcone_bootstrap._Printed):
        sys.stdout = lightcone_bootstrap._Printed(sys.stdout)
    for module in (os, posix):
        module._exit = lightcone_bootstrap._no_exit
        module.abort = lightcone_bootstrap._no_exit
    return Child(name, source, request, limit)
