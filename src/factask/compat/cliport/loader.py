"""Load a GenSim/CLIPort task file unchanged and import it as a factask graph.

**The file is executed** (it is Python): only load files you trust, or use the
batch command, which runs each file in a child process with a time limit.

While a file is loaded, :func:`cliport_aliases` puts a synthetic ``cliport``
package (``cliport.tasks``, ``cliport.tasks.task``, ``cliport.utils.utils``,
``cliport.tasks.primitives``, ``cliport.tasks.grippers``, ``cliport.tasks.cameras``)
and a ``pybullet`` stand-in into ``sys.modules``, mapping to the modules of
:mod:`factask.compat.cliport`, and lends the NumPy 1.x / Python 3.8 names GenSim's
stack had (:mod:`factask.compat.cliport.legacy`); afterwards the previous entries
are restored.
"""

from __future__ import annotations

import contextlib
import random
import signal
import sys
import threading
import traceback
import types
import uuid
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import ValidationError

from factask.compat.cliport import cameras, grippers, primitives, pybullet_stub, task, utils
from factask.compat.cliport.convert import build_graph, kebab, object_names
from factask.compat.cliport.debugging import debugging_stand_ins
from factask.compat.cliport.errors import (
    CliportImportError,
    NoGoals,
    PoseError,
    TaskTimeout,
    Unsupported,
    recording_refusals,
)
from factask.compat.cliport.isolated import FORK_AVAILABLE, run_in_child
from factask.compat.cliport.legacy import legacy_names
from factask.compat.cliport.recorder import FAKE_ASSETS_ROOT, RecordingEnv, Session, session_scope
from factask.compat.cliport.scoring import RavensGoal
from factask.compat.cliport.task import RAVENS_POS_EPS, RAVENS_ROT_EPS, Task
from factask.graph.taskgraph import TaskGraph
from factask.vocabulary.errors import FactaskError, clip

#: Module names the alias context provides.
ALIAS_NAMES = (
    "cliport", "cliport.tasks", "cliport.tasks.task", "cliport.tasks.primitives",
    "cliport.tasks.grippers", "cliport.tasks.cameras", "cliport.utils", "cliport.utils.utils",
    "pybullet",
)


#: Seconds a task file's own code (its module and ``reset``) may run in one import
#: before it is stopped with :class:`TaskTimeout`. Resets take milliseconds; a file
#: that runs this long is in a loop that never ends.
TIME_LIMIT_S = 60.0

#: Seconds between further stops when the task's code swallows the first one (a
#: bare ``except:`` around its loop).
_REFIRE_S = 0.5


class _OutOfTime(BaseException):
    """Raised into the task's code when its time is up; a ``BaseException`` so the
    task's own ``except Exception`` does not swallow it."""


@contextlib.contextmanager
def _time_limit(seconds: float | None,
                on_stop: Callable[[Any], None] | None = None) -> Iterator[None]:
    """Stop the block with :class:`_OutOfTime` after ``seconds`` of wall clock.

    Uses ``SIGALRM``, so only where that exists, in the main thread, and when no
    other alarm is set (a test runner's own timeout keeps its alarm); elsewhere the
    block runs unlimited. Code that catches the stop can go on regardless: for a
    stop that always holds, :func:`import_cliport` runs this in a child process
    that is killed at the limit.

    Args:
        seconds: The limit; None or 0: unlimited.
        on_stop: Called once, with the frame the first stop lands in.
    """
    usable = (seconds is not None and seconds > 0 and hasattr(signal, "setitimer")
              and threading.current_thread() is threading.main_thread())
    if usable and (signal.getitimer(signal.ITIMER_REAL)[0] > 0
                   or signal.getsignal(signal.SIGALRM) not in (signal.SIG_DFL, signal.SIG_IGN,
                                                               None)):
        usable = False
    if not usable:
        yield
        return
    fired: list[bool] = []

    def fire(signum: int, frame: Any) -> None:
        if not fired and on_stop is not None:
            fired.append(True)
            on_stop(frame)
        raise _OutOfTime()

    previous = signal.signal(signal.SIGALRM, fire)
    signal.setitimer(signal.ITIMER_REAL, float(seconds), _REFIRE_S)  # type: ignore[arg-type]
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


@dataclass
class ImportResult:
    """A CLIPort task imported as a factask graph.

    Attributes:
        graph: The validated task graph.
        warnings: Every approximation or dropped detail, in order.
        task_name: The graph's (kebab-case) name.
        class_name: The task class imported.
        goals: CLIPort's goal queue, in order, in factask's object names (for
            :func:`~factask.compat.cliport.scoring.ravens_reward`).
        object_ids: CLIPort object id -> variable name.
        pos_eps: The task's Ravens XY tolerance, metres.
        rot_eps: The task's Ravens yaw tolerance, radians.
    """

    graph: TaskGraph
    warnings: list[str] = field(default_factory=list)
    task_name: str = ""
    class_name: str = ""
    goals: list[RavensGoal] = field(default_factory=list)
    object_ids: dict[int, str] = field(default_factory=dict)
    pos_eps: float = RAVENS_POS_EPS
    rot_eps: float = RAVENS_ROT_EPS


def _package(name: str, **attrs: Any) -> types.ModuleType:
    mod = types.ModuleType(name, f"factask stand-in for {name}")
    mod.__path__ = []  # a package, so submodule imports resolve through sys.modules
    for key, value in attrs.items():
        setattr(mod, key, value)
    return mod


def _tasks_getattr(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    raise Unsupported(f"cliport.tasks.{name}: other CLIPort/GenSim task classes are not "
                      "available; a task file must define its own Task subclass")


def _alias_modules() -> dict[str, types.ModuleType]:
    tasks_pkg = _package("cliport.tasks", Task=Task, task=task, primitives=primitives,
                         grippers=grippers, cameras=cameras)
    tasks_pkg.__getattr__ = _tasks_getattr  # type: ignore[attr-defined]
    utils_pkg = _package("cliport.utils", utils=utils)
    root = _package("cliport", tasks=tasks_pkg, utils=utils_pkg)
    return {
        "cliport": root, "cliport.tasks": tasks_pkg, "cliport.tasks.task": task,
        "cliport.tasks.primitives": primitives, "cliport.tasks.grippers": grippers,
        "cliport.tasks.cameras": cameras, "cliport.utils": utils_pkg,
        "cliport.utils.utils": utils, "pybullet": pybullet_stub,
    }


@contextlib.contextmanager
def cliport_aliases() -> Iterator[None]:
    """Make ``cliport.*`` and ``pybullet`` importable as factask's stand-ins, and
    lend the GenSim-era NumPy / ``random`` names task code uses
    (:func:`~factask.compat.cliport.legacy.legacy_names`) and do-nothing debugging
    modules (:mod:`factask.compat.cliport.debugging`: ``IPython``, ``ipdb``,
    ``breakpoint()``).

    Whatever those names meant before (a real install, nothing) is restored on
    exit, so the aliases never leak into the rest of the process.
    """
    saved = {name: sys.modules.get(name) for name in ALIAS_NAMES}
    sys.modules.update(_alias_modules())
    try:
        with legacy_names(), debugging_stand_ins():
            yield
    finally:
        for name, prev in saved.items():
            if prev is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = prev


@contextlib.contextmanager
def _seeded(seed: int) -> Iterator[None]:
    """Seed ``random`` and ``np.random`` (task code uses them) and restore them after."""
    py_state, np_state = random.getstate(), np.random.get_state()
    random.seed(seed)
    np.random.seed(seed)
    try:
        yield
    finally:
        random.setstate(py_state)
        np.random.set_state(np_state)


def _where(exc: BaseException, path: Path) -> str:
    """'file:line in function: code' of the last traceback frame in the user's file."""
    return _last_in(traceback.extract_tb(exc.__traceback__), path)


def _where_frame(frame: types.FrameType, path: Path) -> str:
    """Like :func:`_where`, for the stack a running frame is in (a signal's frame)."""
    return _last_in(traceback.extract_stack(frame), path)


def _last_in(frames: traceback.StackSummary, path: Path) -> str:
    own = [f for f in frames if Path(f.filename).resolve() == path.resolve()]
    if not own:
        return str(path)
    f = own[-1]
    code = f" `{f.line.strip()}`" if f.line else ""
    return f"{path}:{f.lineno} in {f.name}:{code}"


def _short(exc: ValidationError) -> str:
    """A graph's validation errors in one line each: where, what, and for the sizes a
    task can exceed, the fix (pydantic's text repeats the whole input)."""
    lines = []
    for e in exc.errors(include_url=False):
        where = ".".join(str(x) for x in e.get("loc", ())) or "graph"
        fix = ""
        if e.get("type") == "too_long" and where in ("variables", "factors"):
            fix = (" (fix: fewer objects; a pile or a rope counts as one)" if where ==
                   "variables" else " (fix: fewer goals)")
        lines.append(f"{where}: {e.get('msg', 'invalid')}{fix}")
    return "; ".join(lines)


def _user_error(what: str, exc: BaseException, path: Path) -> CliportImportError:
    cls = Unsupported if isinstance(exc, Unsupported) else CliportImportError
    return cls(f"{what}: {type(exc).__name__}: {clip(exc, 300)} (at {_where(exc, path)})")


def _check_regular_file(path: Path) -> None:
    """Refuse a path that exists but is not a regular file: a FIFO or a device would
    block the read."""
    if path.exists() and not path.is_file():
        raise CliportImportError(f"cannot read {path}: not a regular file (a FIFO, a "
                                 "device or a folder); give a task file")


def _exec_file(path: Path) -> types.ModuleType:
    _check_regular_file(path)
    try:
        source = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise CliportImportError(f"cannot read {path}: {exc}") from None
    try:
        code = compile(source, str(path), "exec")
    except SyntaxError as exc:
        raise CliportImportError(
            f"{path}:{exc.lineno}: syntax error: {exc.msg}"
            + (f" `{clip(exc.text.strip(), 120)}`" if exc.text else "")) from None
    except (RecursionError, MemoryError, ValueError) as exc:  # deep nesting, NUL bytes
        raise CliportImportError(f"{path}: cannot compile: {type(exc).__name__}: "
                                 f"{clip(exc, 200)}") from None
    name = f"factask_cliport_user_{uuid.uuid4().hex[:12]}"
    module = types.ModuleType(name)
    module.__file__ = str(path)
    sys.modules[name] = module  # dataclasses/typing look the module up while it runs
    try:
        exec(code, module.__dict__)
    except CliportImportError:
        raise
    except SystemExit as exc:
        raise CliportImportError(f"loading {path.name} called sys.exit({exc.code!r}): a task "
                                 "file must define its Task class, not run a program") from None
    except Exception as exc:
        raise _user_error(f"loading {path.name} failed", exc, path) from exc
    finally:
        sys.modules.pop(name, None)
    return module


def _camel(stem: str) -> str:
    return "".join(part.capitalize() for part in stem.replace("-", "_").split("_"))


def _pick_class(module: types.ModuleType, path: Path, class_name: str | None) -> type:
    if class_name is not None:
        cls = getattr(module, class_name, None)
        if not (isinstance(cls, type) and issubclass(cls, Task)):
            raise CliportImportError(f"{path}: no Task subclass named {class_name!r}")
        return cls
    own = [v for v in vars(module).values()
           if isinstance(v, type) and issubclass(v, Task) and v is not Task
           and v.__module__ == module.__name__]
    if not own:
        raise CliportImportError(f"{path}: no Task subclass defined (a task file defines "
                                 "`class MyTask(Task):` with `from cliport.tasks.task import "
                                 "Task`)")
    if len(own) == 1:
        return own[0]
    by_name = [c for c in own if c.__name__ == _camel(path.stem)]
    if by_name:
        return by_name[0]
    # GenSim's variants (``FooSeenColors(Foo)``, ``FooUnseenColors(Foo)``) derive from
    # the task itself: the one class every other derives from is the task.
    roots = [c for c in own if all(issubclass(o, c) for o in own)]
    if len(roots) == 1:
        return roots[0]
    raise CliportImportError(f"{path}: several Task subclasses "
                             f"({', '.join(c.__name__ for c in own)}); pick one as "
                             f"{path.name}:{own[0].__name__} (import-cliport: --class)")


def load_task_class(path: str | Path, class_name: str | None = None) -> type:
    """Execute a task file with the CLIPort stand-ins and return its Task class.

    Args:
        path: The ``.py`` file (executed: trusted code only).
        class_name: The class to return; default: the one Task subclass the file
            defines (or the one named after the file, if it defines several).

    Returns:
        The class (a subclass of :class:`factask.compat.cliport.task.Task`).

    Raises:
        CliportImportError: unreadable file, syntax error (with its line), an
            exception while the module runs (with the user's line), or no Task subclass.
    """
    p = Path(path)
    with cliport_aliases():
        module = _exec_file(p)
    return _pick_class(module, p, class_name)


def import_cliport(path: str | Path, class_name: str | None = None,
                   seed: int = 0, on_loaded: Callable[[type], None] | None = None,
                   time_limit: float | None = TIME_LIMIT_S,
                   isolate: bool = True) -> ImportResult:
    """Load a task file, run ``reset`` against a recording env, and build its graph.

    Args:
        path: The ``.py`` file (executed: trusted code only).
        class_name: Which Task subclass (default: see :func:`load_task_class`).
        seed: Seed of every random draw of the reset (``np.random``, ``random``,
            ``get_random_pose``).
        on_loaded: Called with the Task class once the file has run and the class
            is picked, before ``reset`` (the batch worker reports that stage). It
            runs where the file runs: in the child process unless ``isolate`` is False.
        time_limit: Seconds the import may run; None: unlimited.
        isolate: Run the file's code in a forked child process (where ``fork``
            exists), killed at ``time_limit`` whatever the code catches, and whose
            ``os._exit`` ends only itself. False: in this process, stopped by an
            alarm the code can swallow (main thread only, see :func:`_time_limit`;
            the batch worker, itself a killable child, uses this).

    Returns:
        The validated graph, the warnings and the Ravens goal queue.

    Raises:
        CliportImportError: any failure, with a message naming the file and line.
        Unsupported: the task uses something factask does not model (a subclass
            of CliportImportError).
        TaskTimeout: the file's code ran past ``time_limit`` (a subclass of
            CliportImportError).
    """
    p = Path(path)
    if not (isolate and FORK_AVAILABLE):
        return _import(p, class_name, seed, on_loaded, time_limit)
    _check_regular_file(p)  # here: the child would block on it before its limit
    # the alarm stops code that does not swallow it a little before the kill, so the
    # usual error (with the task's own traceback line) comes back first
    alarm = None if not time_limit else time_limit - min(0.5, 0.1 * time_limit)
    return run_in_child(
        lambda note: _import(p, class_name, seed, on_loaded, time_limit, note, alarm),
        time_limit=time_limit or None, what=str(p))


def _import(p: Path, class_name: str | None, seed: int,
            on_loaded: Callable[[type], None] | None, time_limit: float | None,
            on_stop: Callable[[str], None] | None = None,
            alarm_s: float | None = None) -> ImportResult:
    try:
        return _import_once(p, class_name, seed, on_loaded, time_limit, on_stop, alarm_s)
    except NoGoals as exc:
        if class_name is not None or exc.derived is None:
            raise
        # the class picked by default only sets the scene up; the one line of
        # classes the file derives from it (``Extra(Base)``, whose ``reset`` calls
        # ``super().reset(env)`` and queues the goals) ends in the task
        result = _import_once(p, exc.derived, seed, on_loaded, time_limit, on_stop, alarm_s)
        result.warnings.insert(0, f"the file's default class queues no goals ({exc}); "
                                  f"imported {exc.derived}, the class derived from it")
        return result


def _most_derived(module: types.ModuleType, cls: type) -> str | None:
    """The one class of the file deriving from ``cls`` that nothing else derives
    from, when the file's subclasses of ``cls`` form one line; else None."""
    subs = [v for v in vars(module).values()
            if isinstance(v, type) and issubclass(v, cls) and v is not cls
            and v.__module__ == module.__name__]
    leaves = [c for c in subs if not any(o is not c and issubclass(o, c) for o in subs)]
    if len(leaves) == 1 and all(issubclass(leaves[0], c) for c in subs):
        return leaves[0].__name__
    return None


def _run_reset(cls: type, session: Session, p: Path, refused: list[str]) -> Any:
    """Instantiate the task class and run its ``reset`` against a recording env;
    the task's own failures become :class:`CliportImportError` naming its line."""
    try:
        instance = cls()
        instance.set_assets_root(FAKE_ASSETS_ROOT)
        instance.reset(RecordingEnv(session, instance))
    except Unsupported:
        raise
    except SystemExit as exc:
        raise CliportImportError(f"{p}: {cls.__name__}.reset called "
                                 f"sys.exit({exc.code!r})") from None
    except Exception as exc:
        if refused:  # the task caught factask's refusal and failed later
            raise Unsupported(f"{p}: {cls.__name__}.reset failed after factask "
                              f"refused {refused[0]} (the task caught that and "
                              f"went on): {type(exc).__name__}: {exc}") from exc
        raise _user_error(f"{cls.__name__}.reset failed", exc, p) from exc
    return instance


def _import_once(p: Path, class_name: str | None, seed: int,
                 on_loaded: Callable[[type], None] | None,
                 time_limit: float | None = TIME_LIMIT_S,
                 on_stop: Callable[[str], None] | None = None,
                 alarm_s: float | None = None) -> ImportResult:
    """One import in this process; the alarm stops the task's code at ``alarm_s``
    (default ``time_limit``), the messages name ``time_limit``."""
    session = Session(seed=seed, rng=np.random.default_rng(seed))
    stage = f"loading {p.name}"

    def out_of_time(where: str) -> str:
        return (f"{stage} ran past the {time_limit:g} s limit (a loop that never ends? "
                f"--time-limit sets the limit); stopped at {where}")

    def stopped(frame: types.FrameType) -> None:
        if on_stop is not None:
            on_stop(out_of_time(_where_frame(frame, p)))
    try:
        # The file's own prints go to stderr: stdout is the command's (one JSON value
        # under --json), and a task that prints must not make it unreadable.
        with cliport_aliases(), _seeded(seed), session_scope(session), \
                contextlib.redirect_stdout(sys.stderr):
            try:
                with _time_limit(time_limit if alarm_s is None else alarm_s, stopped), \
                        recording_refusals() as refused:
                    module = _exec_file(p)
                    cls = _pick_class(module, p, class_name)
                    if on_loaded is not None:
                        on_loaded(cls)
                    stage = f"{cls.__name__}.reset"
                    instance = _run_reset(cls, session, p, refused)
            except _OutOfTime as exc:
                raise TaskTimeout(out_of_time(_where(exc, p))) from None
            for message in dict.fromkeys(refused):
                session.warn(f"the task caught factask's refusal and went on without it: "
                             f"{message}")
            try:
                graph, goals = build_graph(instance, session, cls.__name__)
            except NoGoals as exc:
                err = NoGoals(f"{p}: {cls.__name__}: {exc}")
                err.derived = _most_derived(module, cls) if class_name is None else None
                raise err from exc
            except CliportImportError as exc:
                raise type(exc)(f"{p}: {cls.__name__}: {exc}") from exc
            except PoseError as exc:  # a malformed pose in a goal: not a graph problem
                raise CliportImportError(f"{p}: {cls.__name__}: the recorded goals could "
                                         f"not be converted: {type(exc).__name__}: {exc}"
                                         ) from exc
            except ValidationError as exc:
                raise CliportImportError(f"{p}: {cls.__name__}: the recorded scene is not "
                                         f"a valid graph: {_short(exc)}") from exc
            except FactaskError as exc:
                raise CliportImportError(f"{p}: {cls.__name__}: the recorded scene is not "
                                         f"a valid graph: {exc}") from exc
            except Exception as exc:  # e.g. a goal field of the wrong type
                raise CliportImportError(f"{p}: {cls.__name__}: the recorded goals could "
                                         f"not be converted: {type(exc).__name__}: {exc}"
                                         ) from exc
    finally:
        session.close()
    names = {v.name for v in graph.variables}
    return ImportResult(
        graph=graph, warnings=list(session.warnings), task_name=kebab(cls.__name__),
        class_name=cls.__name__, goals=goals,
        object_ids={oid: n for oid, n in object_names(list(session.objects.values())).items()
                    if n in names},
        pos_eps=float(instance.pos_eps), rot_eps=float(instance.rot_eps))

