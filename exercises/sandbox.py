"""The student's kernel, fenced: bubblewrap, a memory limit, its own scratch folder.

The grader (grade.py) runs each submitted notebook in kernels started by :class:`StudentKernel`
(one at a time; a fresh one when a kernel dies or hangs). Each kernel's launch command is this
file run as a script (``python sandbox.py --memory BYTES -- COMMAND...``): it sets
``RLIMIT_AS`` (a memory hog gets MemoryError, not the machine) and ``exec``s ``COMMAND``, which
is, with bubblewrap (Debian's ``bubblewrap``, :func:`bwrap_command`):

* a new process tree: a PID namespace whose first process dies with the grader
  (``--unshare-pid --die-with-parent``), so that every process the notebook started is gone
  when its kernel is stopped; a new session (``--new-session``: no terminal to type into), no
  network (``--unshare-net``), no System V IPC shared with the machine (``--unshare-ipc``);
* the whole system read-only (``--ro-bind / /``, a fresh ``/dev`` and ``/proc``), with the
  places that hold other people's data or live sockets (``/tmp``, ``/var/tmp``, ``/run``, the
  home folder, Jupyter's runtime folder) and the course's places (its repository, the class's
  submissions, the grader's outputs) replaced by empty read-only folders. What the kernel needs
  is put back, read-only: the Python installation and its ``sys.path``, rsgeo and
  rsgeo_course (their data and translations) and the notebook being graded; never the
  course's exercise folder, its build or its history (the worked solutions);
* one writable folder, the kernel's scratch folder (its working folder, ``HOME``, ``TMPDIR``
  and caches: Numba's, matplotlib's and IPython's, seeded from the grader's so that nothing is
  compiled twice), and the kernel's socket folder; its connection file is read-only;
* a clean environment: only the locale, thread and PROJ settings of the grader's.

Without bubblewrap the grader refuses to run unless told ``--unsafe``; then the kernel runs
with the memory limit, the scratch folder and an audit hook (:data:`GUARD`) that refuses the
plain ways to read the solutions or write into the course. An audit hook is no security
boundary (``ctypes``, ``dir_fd``, a process that outlives its kernel get past it): every row
graded that way says so.

The kernel's IPython is told before any student code runs (``exec_lines``) to install the
answers' reader (judge.py), and not to watch its parent (it sees PID 1 in its namespace;
``--die-with-parent`` does that job).
"""

import asyncio
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from queue import Empty

DEFAULT_MEMORY = 3 * 2 ** 30        # bytes of address space a student kernel may take
START_TIMEOUT = 120                 # seconds a kernel may take to answer its first request
INTERRUPT_GRACE = 5                 # seconds a kernel has to stop after an interrupt
DEV_SHM_BYTES = 64 * 2 ** 20        # /dev/shm in the sandbox (it is memory)
# where other users' and programs' data and live sockets are (a socket stays connectable
# through a read-only mount: dbus, ssh-agent, tmux, another Jupyter): hidden in the sandbox
PRIVATE_PLACES = ("/tmp", "/var/tmp", "/run", "/var/run")
# the grader's settings a kernel keeps; everything else in its environment is dropped
KEPT_ENVIRONMENT = ("PATH", "LANG", "LANGUAGE", "TZ", "OMP_NUM_THREADS", "MKL_NUM_THREADS",
                    "OPENBLAS_NUM_THREADS", "PROJ_DATA", "PROJ_LIB", "GDAL_DATA", "PYTHONPATH")
MAX_MESSAGE_BYTES = 64 * 2 ** 20    # a larger reply from a kernel is dropped, never read
KEPT_PREFIXES = ("LC_", "RSGEO_", "NUMBA_")


class SandboxError(RuntimeError):
    """The grader cannot start a student kernel the way it must (never a student's doing)."""


def bwrap_path():
    """The bubblewrap executable, or None where it is not installed."""
    return shutil.which("bwrap")


def _real(path):
    return os.path.realpath(os.fspath(path))


def _inside(path, folder):
    """Whether ``path`` is ``folder`` or below it (both real paths)."""
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)


# run by the kernels' interpreter, in their environment: what it reads Python and ``packages`` from
_NEEDS = """
import importlib.util, json, os, site, sys
paths = [sys.prefix, sys.exec_prefix, sys.base_prefix, sys.base_exec_prefix,
         os.path.dirname(sys.executable), *sys.path, *site.getsitepackages()]
if site.ENABLE_USER_SITE:
    paths.append(site.getusersitepackages())
for name in sys.argv[1:]:
    spec = importlib.util.find_spec(name)
    if spec is not None:
        paths += list(spec.submodule_search_locations or [os.path.dirname(spec.origin)])
print(json.dumps(paths))
"""


def needed_paths(packages=("rsgeo", "rsgeo_course"), python=None):
    """What a kernel needs to read: its Python installation, its ``sys.path`` and ``packages``.

    Asks the kernels' interpreter (``python``, default this one), started as a kernel is (in a
    kernel's environment, :func:`kernel_environment`), so that the grader's own script folder
    or test folders are not among them.

    Returns
    -------
    list of str
        Existing paths (as given, and real): the interpreter's prefixes and folder, every
        ``sys.path`` entry, the site-packages folders, each package's folder (an editable
        install's package lives outside site-packages) and the PROJ or GDAL data folders the
        environment names.

    Raises
    ------
    SandboxError
        If the interpreter cannot say.
    """
    python = python or sys.executable
    with tempfile.TemporaryDirectory(prefix="rsgeo-probe-") as work:
        run = subprocess.run([python, "-c", _NEEDS, *packages], capture_output=True, text=True,
                             cwd=work, env=kernel_environment(work), timeout=120)
    if run.returncode != 0:
        raise SandboxError(f"{python} cannot list its paths: {run.stderr.strip()[-500:]}")
    paths = {*json.loads(run.stdout), os.path.dirname(_real(python))}
    paths.update(os.environ[name] for name in ("PROJ_DATA", "PROJ_LIB", "GDAL_DATA")
                 if os.environ.get(name))
    found = set()
    for path in paths:
        if path and os.path.isabs(path) and os.path.exists(path):
            found.update({os.path.abspath(path), _real(path)})
    return sorted(found)


def private_places():
    """The machine's places a kernel must not see (:data:`PRIVATE_PLACES`, the home folder,
    the runtime folders of the session and of Jupyter, the temporary folder), real paths."""
    places = [*PRIVATE_PLACES, tempfile.gettempdir(), os.path.expanduser("~"),
              os.environ.get("XDG_RUNTIME_DIR", "")]
    try:
        from jupyter_core.paths import jupyter_runtime_dir

        places.append(jupyter_runtime_dir())
    except ImportError:
        pass
    return sorted({_real(place) for place in places if place and os.path.isdir(place)
                   and _real(place) != os.sep})


@dataclass
class Fence:
    """What a student kernel may see, change and take (see the module's docstring).

    Parameters
    ----------
    memory : int
        Bytes of address space (``RLIMIT_AS``).
    hidden : list of str
        Folders replaced by empty read-only ones (the machine's private places, the course's
        repository); what ``readable`` names inside them is put back.
    secret : list of str
        Folders never shown, not even a part of them (the course's exercises and their build,
        the submissions, the grader's outputs): a ``readable`` path that overlaps one is left
        out.
    readable : list of str
        Paths the kernel needs to read (:func:`needed_paths`).
    blanked : list of str
        Files shown empty (the grader's outputs).
    folder : str
        The grader's own folder for the kernels' scratch and socket folders (hidden; each
        kernel sees its own).
    unsafe : bool
        Run without bubblewrap (an audit hook instead), when it is not installed.
    protected : list of str
        Without bubblewrap: folders the audit hook refuses writes into.
    """

    memory: int = DEFAULT_MEMORY
    hidden: list = field(default_factory=list)
    secret: list = field(default_factory=list)
    readable: list = field(default_factory=list)
    blanked: list = field(default_factory=list)
    folder: str = ""
    unsafe: bool = False
    protected: list = field(default_factory=list)


def bwrap_command(command, work, sockets, fence, notebook=None, connection_file=None):
    """``command`` inside bubblewrap, as the module's docstring says.

    Parameters
    ----------
    command : list of str
        The kernel's command.
    work : str
        The kernel's scratch folder: writable, its working folder.
    sockets : str
        The kernel's socket folder (writable: the kernel creates its sockets there).
    fence : Fence
        What is hidden, kept secret, readable and blanked.
    notebook : str, optional
        The notebook being graded, shown read-only where it is (unless a symbolic link is on
        its path).
    connection_file : str, optional
        Bound read-only over itself.

    Returns
    -------
    list of str
    """
    secret = [_real(path) for path in fence.secret]
    hidden = {_real(path) for path in [*fence.hidden, *fence.secret, fence.folder]
              if path and os.path.isdir(path) and _real(path) != os.sep}

    def overlaps_secret(path):
        return any(_inside(path, folder) or _inside(folder, path) for folder in secret)

    # what is needed inside a hidden folder is put back; never a secret, never a hidden
    # folder itself; mounts go shallow to deep, so that a hidden folder inside a readable one
    # (the course inside a home folder on sys.path) is hidden again after it
    readable = {_real(path) for path in fence.readable if os.path.exists(path)}
    readable = {path for path in readable if path not in hidden and not overlaps_secret(path)
                and any(_inside(path, folder) for folder in hidden)}

    def shown_by(path, other):          # ``other``'s bind shows ``path`` already
        return other != path and _inside(path, other) and not any(
            _inside(folder, other) and folder != other and _inside(path, folder)
            for folder in hidden)

    readable = {path for path in readable if not any(shown_by(path, other) for other in readable)}
    mounts = sorted([(path.count(os.sep), 0, path) for path in hidden]
                    + [(path.count(os.sep), 1, path) for path in readable])
    wrapped = [bwrap_path(), "--ro-bind", "/", "/", "--dev", "/dev", "--proc", "/proc",
               "--perms", "1777", "--size", str(DEV_SHM_BYTES), "--tmpfs", "/dev/shm",
               "--unshare-pid", "--unshare-net", "--unshare-ipc", "--die-with-parent",
               "--new-session"]
    for _depth, kind, path in mounts:
        wrapped += ["--tmpfs", path] if kind == 0 else ["--ro-bind", path, path]
    if notebook and os.path.isfile(notebook) and _real(notebook) == os.path.abspath(notebook):
        wrapped += ["--ro-bind", _real(notebook), _real(notebook)]     # no link on its way
    for path in fence.blanked:           # an output file in a folder that is not hidden
        if os.path.isfile(path) and not any(_inside(_real(path), folder) for folder in hidden):
            wrapped += ["--ro-bind", os.devnull, _real(path)]
    wrapped += ["--bind", _real(work), _real(work), "--bind", _real(sockets), _real(sockets)]
    if connection_file:
        wrapped += ["--ro-bind", _real(connection_file), _real(connection_file)]
    for folder in sorted(hidden):
        wrapped += ["--remount-ro", folder]
    wrapped += ["--clearenv"]
    for name, value in kernel_environment(work).items():
        wrapped += ["--setenv", name, value]
    return wrapped + ["--chdir", _real(work), "--", *command]


def kernel_environment(work, base=None):
    """The environment of a kernel whose scratch folder is ``work``: the settings of
    :data:`KEPT_ENVIRONMENT` and :data:`KEPT_PREFIXES` from ``base`` (the grader's), and its
    home, temporary folder and caches in ``work``."""
    base = os.environ if base is None else base
    env = {name: value for name, value in base.items()
           if name in KEPT_ENVIRONMENT or name.startswith(KEPT_PREFIXES)}
    work = _real(work)
    env.update(HOME=work, TMPDIR=work, MPLBACKEND="Agg", PYTHONDONTWRITEBYTECODE="1",
               MPLCONFIGDIR=os.path.join(work, ".matplotlib"),
               NUMBA_CACHE_DIR=os.path.join(work, ".numba"),
               IPYTHONDIR=os.path.join(work, ".ipython"),
               XDG_CACHE_HOME=os.path.join(work, ".cache"),
               XDG_CONFIG_HOME=os.path.join(work, ".config"),
               JUPYTER_PLATFORM_DIRS="1", PYDEVD_DISABLE_FILE_VALIDATION="1")
    env.setdefault("PATH", os.defpath)
    return env


def seed_caches(work, packages=("rsgeo",)):
    """Copy the grader's Numba cache of ``packages`` and matplotlib's font list into the
    kernel's scratch folder ``work`` (where :func:`kernel_environment` points Numba and
    matplotlib), so that the kernel compiles and scans nothing the grader already has.
    Does nothing for what is not found."""
    import importlib.util

    work = Path(work)
    try:
        from numba.core.caching import _CacheLocator
    except ImportError:
        _CacheLocator = None
    for name in packages if _CacheLocator is not None else ():
        spec = importlib.util.find_spec(name)
        for folder in (spec.submodule_search_locations or []) if spec else []:
            for cache in Path(folder).rglob("__pycache__"):
                files = [path for path in cache.iterdir() if path.suffix in (".nbi", ".nbc")
                         or path.name == "rsgeo-compiled-sources.sha256"]
                if not files:
                    continue
                target = work / ".numba" / _CacheLocator.get_suitable_cache_subpath(
                    str(cache.parent / "module.py"))
                target.mkdir(parents=True, exist_ok=True)
                for path in files:
                    shutil.copy2(path, target / path.name)
    try:
        import matplotlib

        fonts = list(Path(matplotlib.get_cachedir()).glob("fontlist-*.json"))
    except Exception:                                  # noqa: BLE001 - no cache to seed
        fonts = []
    if fonts:
        (work / ".matplotlib").mkdir(exist_ok=True)
        for path in fonts:
            shutil.copy2(path, work / ".matplotlib" / path.name)


# Installed by the kernel at its start (IPython exec_lines) when it runs without bwrap
# (--unsafe). Audit hooks cannot be removed; the closure keeps the folders out of the
# student's namespace. Not a security boundary (see the module's docstring).
GUARD = '''
def _install_guard(hidden, protected):
    import os, sys
    hidden = tuple(os.path.realpath(path) + os.sep for path in hidden)
    protected = tuple(os.path.realpath(path) + os.sep for path in protected)
    reads = {{"open", "os.listdir", "os.scandir", "glob.glob", "os.chdir"}}
    changes = {{"os.remove", "os.rename", "os.rmdir", "os.mkdir", "shutil.rmtree", "os.chmod",
               "os.truncate", "os.symlink", "os.link", "shutil.copyfile", "shutil.move"}}
    programs = {{"subprocess.Popen", "os.system", "os.exec", "os.posix_spawn", "os.spawn",
                "os.fork", "os.forkpty", "pty.spawn"}}

    def inside(path, folders):
        try:
            path = os.path.realpath(os.fsdecode(path)) + os.sep
        except (TypeError, ValueError):
            return False
        return path.startswith(folders)

    def guard(event, args):
        if event in programs:
            raise PermissionError("the grader runs no programs from a submission")
        if event in reads or event in changes:
            if args and isinstance(args[0], (str, bytes, os.PathLike)):
                if inside(args[0], hidden):
                    raise PermissionError("the course's folders are not readable when grading")
                writing = event in changes or (event == "open" and len(args) > 1 and (
                    any(flag in str(args[1] or "") for flag in "wax+")
                    or (isinstance(args[2], int) and args[2] & (os.O_WRONLY | os.O_RDWR))))
                if writing and inside(args[0], protected):
                    raise PermissionError("a submission may write only in its own folder")
    sys.addaudithook(guard)
_install_guard({hidden!r}, {protected!r})
del _install_guard
'''


def _manager_class():
    from jupyter_client.manager import AsyncKernelManager

    class SandboxedKernelManager(AsyncKernelManager):
        """A kernel over Unix sockets in its own folder, launched through this file's wrapper
        (in bubblewrap unless the fence is unsafe), with its answers' reader installed."""

        def __init__(self, fence, work, sockets, exec_lines=(), notebook=None, **kwargs):
            kwargs.setdefault("transport", "ipc")
            kwargs.setdefault("ip", os.path.join(sockets, "kernel"))
            kwargs.setdefault("connection_file", os.path.join(sockets, "connection.json"))
            super().__init__(**kwargs)
            self.fence, self.work, self.sockets = fence, work, sockets
            self.exec_lines, self.notebook = list(exec_lines), notebook

        def format_kernel_cmd(self, extra_arguments=None):
            extra = [*(extra_arguments or []), "--HistoryManager.enabled=False"]
            lines = list(self.exec_lines)
            if self.fence.unsafe:
                lines.insert(0, GUARD.format(hidden=self.fence.secret,
                                             protected=self.fence.protected
                                             + self.fence.secret))
            else:       # it sees PID 1 as its parent: --die-with-parent watches the grader
                extra.append("--IPKernelApp.parent_handle=0")
            if lines:
                extra.append("--IPKernelApp.exec_lines=" + json.dumps(lines))
            command = super().format_kernel_cmd(extra)
            if not self.fence.unsafe:
                command = bwrap_command(command, self.work, self.sockets, self.fence,
                                        self.notebook, self.connection_file)
            return [sys.executable, os.path.abspath(__file__), "--memory",
                    str(self.fence.memory), "--", *command]

    return SandboxedKernelManager


@dataclass
class Reply:
    """What became of one request: ``status`` "ok", "error" (the cell raised; ``content`` has
    its ``ename`` and ``evalue``), "timeout" (interrupted after its time), "hung" (it did not
    stop when interrupted: the kernel is stopped) or "dead" (the kernel died)."""

    status: str
    content: dict = field(default_factory=dict)


class StudentKernel:
    """One student kernel at a time, in a fresh scratch folder each, restartable.

    Parameters
    ----------
    fence : Fence
    notebook : str, optional
        The notebook being graded (shown read-only to the kernel).
    exec_lines : list of str
        Code the kernel runs at its start, before any student code.
    """

    def __init__(self, fence, notebook=None, exec_lines=()):
        self.fence, self.notebook, self.exec_lines = fence, notebook, list(exec_lines)
        self.manager = self.client = self.folder = self.log = None
        self.starts, self.last_words = 0, ""

    async def start(self, timeout=START_TIMEOUT):
        """Start a fresh kernel and wait until it answers.

        Raises
        ------
        SandboxError
            If it dies or does not answer within ``timeout`` seconds (with what it wrote on
            its standard error: bubblewrap's message when bubblewrap cannot run).
        """
        await self.stop()
        if not self.fence.unsafe and bwrap_path() is None:
            raise SandboxError("bubblewrap (bwrap) is not installed")
        self.starts += 1
        parent = self.fence.folder or None
        self.folder = tempfile.mkdtemp(prefix="kernel-", dir=parent)
        work, sockets = (os.path.join(self.folder, name) for name in ("scratch", "sockets"))
        for path in (work, sockets):
            os.mkdir(path, 0o700)
        seed_caches(work)
        self.log = os.path.join(self.folder, "kernel.log")
        manager_class = _manager_class()
        self.manager = manager_class(self.fence, work, sockets, self.exec_lines, self.notebook,
                                     kernel_name="python3")
        launch = {"env": kernel_environment(work)} if self.fence.unsafe else {}
        with open(self.log, "wb") as log:
            try:
                await self.manager.start_kernel(cwd=work, stdout=log, stderr=log, **launch)
            except Exception as error:             # noqa: BLE001 - any failure to launch
                raise SandboxError(f"the kernel could not be launched: {error}") from error
        import zmq

        self.client = self.manager.client()
        # a tampered kernel's 1 GB reply would fill the grader's memory: zmq drops it
        self.client.context.setsockopt(zmq.MAXMSGSIZE, MAX_MESSAGE_BYTES)
        self.client.start_channels(shell=True, iopub=False, stdin=False, hb=False, control=True)
        reply = await self._request(self.client.kernel_info(), timeout, interrupt=False)
        if reply.status != "ok":
            why = "died" if reply.status == "dead" else f"did not answer in {timeout:.0f} s"
            raise SandboxError(f"the kernel {why} at its start; it wrote: {self.log_tail()}")

    def log_tail(self, size=1500):
        """The end of what the current (else the last) kernel wrote on its standard output
        and error."""
        try:
            text = Path(self.log).read_bytes()[-size:].decode("utf-8", "replace").strip()
        except (OSError, TypeError):
            text = self.last_words
        return text or "(nothing)"

    async def execute(self, code, timeout, user_expressions=None, silent=False):
        """Run ``code``; interrupt it after ``timeout`` seconds; see :class:`Reply`."""
        if self.client is None:
            return Reply("dead")
        msg_id = self.client.execute(code, silent=silent, store_history=not silent,
                                     user_expressions=user_expressions or {},
                                     allow_stdin=False, stop_on_error=False)
        return await self._request(msg_id, timeout)

    async def _request(self, msg_id, timeout, interrupt=True):
        deadline, stop = time.monotonic() + timeout, None
        while True:
            now = time.monotonic()
            wait = (stop or deadline) - now
            if wait > 0:
                try:
                    message = await self.client.get_shell_msg(timeout=min(wait, 1.0))
                except Empty:
                    message = None
                if message is not None and message["parent_header"].get("msg_id") == msg_id:
                    content = message["content"]
                    if stop is not None:
                        return Reply("timeout", content)
                    return Reply(content.get("status", "error"), content)
                if message is not None:
                    continue                           # the late reply of an earlier request
            if not await self.manager.is_alive():
                await self.stop()
                return Reply("dead")
            if time.monotonic() < (stop or deadline):
                continue
            if stop is not None or not interrupt:
                await self.stop()
                return Reply("hung")
            self.client.control_channel.send(self.client.session.msg("interrupt_request", {}))
            stop = time.monotonic() + INTERRUPT_GRACE

    async def stop(self):
        """Stop the kernel: its whole process tree (the sandbox's PID namespace) is killed."""
        if self.client is not None:
            self.client.stop_channels()
            self.client = None
        if self.manager is not None:
            manager, self.manager = self.manager, None
            try:
                if manager.has_kernel:
                    await manager.shutdown_kernel(now=True)
            except Exception:                          # noqa: BLE001 - it is gone either way
                pass
            kernel = getattr(manager.provisioner, "process", None)
            if kernel is not None and kernel.poll() is None:
                kernel.kill()
        if self.folder is not None:
            self.last_words = self.log_tail()
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = self.log = None


async def _check(fence, exec_lines, probe, timeout):
    kernel = StudentKernel(fence, exec_lines=exec_lines)
    try:
        await kernel.start(timeout)
        reply = await kernel.execute(probe["code"], timeout,
                                     user_expressions=probe.get("expressions"))
        if reply.status != "ok":
            raise SandboxError(f"a test cell gave {reply.status} "
                               f"({reply.content.get('ename', '')}: "
                               f"{reply.content.get('evalue', '')}); the kernel wrote: "
                               f"{kernel.log_tail()}")
        return reply
    finally:
        await kernel.stop()


def preflight(fence, exec_lines=(), probe=None, timeout=START_TIMEOUT):
    """Start one kernel as the students' will be and run ``probe`` in it.

    Parameters
    ----------
    fence : Fence
    exec_lines : list of str
        As :class:`StudentKernel`'s.
    probe : dict, optional
        ``{"code": ..., "expressions": {...}}``: a cell and user expressions (default: import
        rsgeo and rsgeo_course.exercises).

    Returns
    -------
    Reply
        The probe's reply (``content["user_expressions"]``).

    Raises
    ------
    SandboxError
        If the kernel cannot start or the probe fails: bubblewrap's or the kernel's message.
    """
    probe = probe or {"code": "import rsgeo, rsgeo_course.exercises"}
    return asyncio.run(_check(fence, exec_lines, probe, timeout))


def main(argv):
    """The launch wrapper: limit memory, then exec the command (bubblewrap, or the kernel)."""
    import argparse
    import resource

    parser = argparse.ArgumentParser()
    parser.add_argument("--memory", type=int, required=True)
    parser.add_argument("command", nargs=argparse.REMAINDER)
    options = parser.parse_args(argv)
    command = options.command[1:] if options.command[:1] == ["--"] else options.command
    resource.setrlimit(resource.RLIMIT_AS, (options.memory, options.memory))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    os.execvp(command[0], command)


if __name__ == "__main__":
    main(sys.argv[1:])
