#!/usr/bin/python3
"""Run a command and write the CPU seconds (user + sys) it and its children used to OUT, and its peak RSS.

On a shared machine the wall-clock of a run grows whenever other processes take the cores; the CPU time
of the run does not (to first order), so report.py shows both. maxrss_kB is the peak resident set of the
largest single process among the children (Linux ru_maxrss, kB): the code itself at 1 thread or rank (mpirun's
launcher is smaller), one rank's at 2 ranks. Usage: cputime.py OUT -- CMD ARGS...
"""
import resource
import subprocess
import sys


def main():
    out = sys.argv[1]
    if sys.argv[2] != "--":
        sys.exit("usage: cputime.py OUT -- CMD ARGS...")
    rc = subprocess.call(sys.argv[3:])
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(out, "w") as f:
        f.write("cpu_s %.6f\nuser_s %.6f\nsys_s %.6f\nrc %d\nmaxrss_kB %d\n" % (
            ru.ru_utime + ru.ru_stime, ru.ru_utime, ru.ru_stime, rc, ru.ru_maxrss))
    sys.exit(rc)


if __name__ == "__main__":
    main()
