"""The student's kernel, fenced: a memory limit, an empty folder, and bubblewrap where it exists.

The grader (grade.py) starts one kernel per submission through :class:`SandboxedKernelManager`.
Its launch command is wrapped by this file run as a script (``python sandbox.py --memory BYTES
-- COMMAND...``): it sets ``RLIMIT_AS`` (a memory hog gets MemoryError, not the machine) and
``exec``s the command, inside ``bwrap`` when Debian's bubblewrap is installed:

* with bwrap: no network (``--unshare-net``), the whole system read-only, the kernel's own
  folders writable, and the course's exercise folder (the worked solutions), the submissions and
  the grader's output folder replaced by empty folders;
* without bwrap (the fallback, reported in the grades' ``note`` column): the memory limit, the
  empty folder, and an audit hook (:data:`GUARD`, installed at the kernel's start) that refuses to
  open, list or change anything in those folders and to write anywhere in the course's
  repository, and refuses to start programs. An audit hook stops a notebook that reads the
  solutions through ``rsgeo.__file__`` or writes into the course folder; it is not a security
  boundary against a student who attacks the machine (ctypes), which bwrap or a container is.
"""

import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "book", "_ext"))
from offline_book import IPCKernelManager  # noqa: E402

DEFAULT_MEMORY = 3 * 2 ** 30        # bytes of address space a student kernel may take


def bwrap_path():
    """The bubblewrap executable, or None where it is not installed."""
    return shutil.which("bwrap")


# Installed by the kernel at its start (IPython exec_lines) when bwrap is missing. Audit hooks
# cannot be removed; the closure keeps the folders out of the student's namespace.
GUARD = '''
def _install_guard(hidden, protected):
    import os, sys
    hidden = tuple(os.path.realpath(path) + os.sep for path in hidden)
    protected = tuple(os.path.realpath(path) + os.sep for path in protected)
    reads = {{"open", "os.listdir", "os.scandir", "glob.glob", "os.chdir"}}
    changes = {{"os.remove", "os.rename", "os.rmdir", "os.mkdir", "shutil.rmtree", "os.chmod",
               "os.truncate", "os.symlink", "os.link", "shutil.copyfile", "shutil.move"}}
    programs = {{"subprocess.Popen", "os.system", "os.exec", "os.posix_spawn", "os.spawn",
                "os.fork", "pty.spawn"}}

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


class SandboxedKernelManager(IPCKernelManager):
    """An IPC kernel launched through this file's wrapper (see the module's docstring).

    Parameters
    ----------
    memory : int
        Bytes of address space (``RLIMIT_AS``).
    hidden : list of str
        Folders the kernel may not see (the course's exercises, the submissions, the output).
    protected : list of str
        Folders it may not write into (the repository, plus ``hidden``).
    work : str
        The kernel's own folder (its working directory), writable.
    """

    def __init__(self, memory=DEFAULT_MEMORY, hidden=(), protected=(), work=None, **kwargs):
        super().__init__(**kwargs)
        self.memory, self.hidden, self.protected = int(memory), list(hidden), list(protected)
        self.work = work or tempfile.gettempdir()

    def format_kernel_cmd(self, extra_arguments=None):
        extra = list(extra_arguments or [])
        if bwrap_path() is None:
            guard = GUARD.format(hidden=self.hidden, protected=self.protected + self.hidden)
            extra.append("--IPKernelApp.exec_lines=" + json.dumps([guard]))
        command = super().format_kernel_cmd(extra)
        return [sys.executable, os.path.abspath(__file__), "--memory", str(self.memory),
                "--work", self.work, "--sockets", self._socket_folder,
                *[item for folder in self.hidden for item in ("--hide", folder)], "--",
                *command]


def bwrap_command(command, work, sockets, hidden):
    """``command`` inside bubblewrap: read-only system, no network, ``hidden`` emptied."""
    wrapped = [bwrap_path(), "--ro-bind", "/", "/", "--dev", "/dev", "--proc", "/proc",
               "--tmpfs", "/tmp", "--bind", work, work, "--bind", sockets, sockets,
               "--unshare-net", "--unshare-pid", "--die-with-parent", "--chdir", work]
    runtime = os.environ.get("JUPYTER_RUNTIME_DIR")
    for folder in hidden:
        if os.path.isdir(folder):
            wrapped += ["--tmpfs", os.path.realpath(folder)]
    if runtime and os.path.isdir(runtime):
        wrapped += ["--ro-bind", runtime, runtime]
    return wrapped + ["--", *command]


def main(argv):
    """The launch wrapper: limit memory, then exec the kernel (in bwrap when present)."""
    import argparse
    import resource

    parser = argparse.ArgumentParser()
    parser.add_argument("--memory", type=int, required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--sockets", required=True)
    parser.add_argument("--hide", action="append", default=[])
    parser.add_argument("command", nargs=argparse.REMAINDER)
    options = parser.parse_args(argv)
    command = options.command[1:] if options.command[:1] == ["--"] else options.command
    resource.setrlimit(resource.RLIMIT_AS, (options.memory, options.memory))
    if bwrap_path() is not None:
        command = bwrap_command(command, options.work, options.sockets, options.hide)
    os.chdir(options.work)
    os.execvp(command[0], command)


if __name__ == "__main__":
    main(sys.argv[1:])
