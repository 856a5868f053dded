"""A whole process's cost, for the bench scripts that time programs against each other."""
import os
import time


def run_rusage(cmd):
    """CPU seconds (user + system of the process and the children it waited for), peak RSS
    in MiB, wall seconds. Started by posix_spawn: a forked Python would count its own work
    before exec as the child's. Exits where the command fails."""
    t0 = time.perf_counter()
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        pid = os.posix_spawnp(cmd[0], cmd, os.environ,
                              file_actions=[(os.POSIX_SPAWN_DUP2, null, 1), (os.POSIX_SPAWN_DUP2, null, 2)])
    finally:
        os.close(null)
    _, status, ru = os.wait4(pid, 0)
    wall = time.perf_counter() - t0
    if status != 0:
        raise SystemExit(f"{cmd}: exit status {status}")
    return ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024, wall
