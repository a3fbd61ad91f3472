"""One owner per output folder for the scripts (doc/user-guide.md, "One run,
one folder"): the lock that ballistic_sweep.py and identify_charmetant.py
take on their output folders, as the executable does on its own."""
import fcntl
import os
import socket

# The locks this process holds (kept open to the end: closing one would
# release it).
_held = []


def hold_folder(folder, lock_name, what, option, error):
    """Take an exclusive lock (fcntl.flock) on FOLDER/LOCK_NAME, held until
    the process ends (the kernel releases it however the process ends). A
    second process on the same folder gets ERROR (the script's one-line
    failure) naming OPTION, the folder and the holder's PID and host; WHAT
    names the kind of run ("sweep")."""
    path = os.path.join(folder, lock_name)
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    except OSError as e:
        raise error("%s %s: cannot create the lock %s: %s"
                    % (option, folder, path, e.strerror or e))
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        try:
            holder = os.pread(fd, 200, 0).decode(errors="replace").split()
        except OSError:
            holder = []
        os.close(fd)
        raise error("%s %s is in use by another %s: process %s on host %s "
                    "holds its lock %s; wait for it to end, or choose "
                    "another %s"
                    % (option, folder, what,
                       holder[0] if holder else "(starting)",
                       holder[1] if len(holder) > 1 else "?", path, option))
    os.ftruncate(fd, 0)
    os.pwrite(fd, ("%d %s\n" % (os.getpid(), socket.gethostname())).encode(),
              0)
    _held.append(fd)
