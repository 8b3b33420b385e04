"""docs/benchmarks.md "The analysis's time left": runs `relight analyze` on a
terminal (a pseudo-terminal, so that it draws its progress lines), stamps
each line with the time, and prints what `(all: ~... left)` said at each
quarter of each render against the time the renders then took to the end
of the last one, and to the program's exit:
    time_left.py SCENE.json OUT_DIR [RELIGHT]   (RELIGHT: default build/src/cli/relight)"""
import os
import pty
import re
import sys
import time

RENDERS = r"(direct light|illumination|initial illumination|interreflection \d+|rendered back|residual)"


def stamped_lines(command):
    start, pending, lines = time.time(), b"", []

    def read(fd):
        nonlocal pending
        data = os.read(fd, 4096)
        pending += data
        *complete, pending = re.split(rb"[\r\n]", pending)
        lines.extend((time.time() - start, c.decode(errors="replace").strip()) for c in complete if c.strip())
        return data

    with open(os.devnull, "wb") as devnull:
        saved = os.dup(1)
        os.dup2(devnull.fileno(), 1)  # the child's drawing, not ours
        try:
            pty.spawn(command, read)
        finally:
            os.dup2(saved, 1)
    return lines, time.time() - start


def seconds(h, m, s):
    return int((h or "0h")[:-1]) * 3600 + int((m or "0m")[:-1]) * 60 + int(s)


def main(scene, out, relight="build/src/cli/relight"):
    lines, exit_time = stamped_lines([relight, "analyze", scene, "-o", out])
    said, last_end = [], None
    for t, line in lines:
        m = re.match(RENDERS + r"\s+\[[#.]*\]\s+(\d+)%.*all: ~(\d+h)?(\d+m)?(\d+)s left", line)
        if m:
            said.append((t, m.group(1), int(m.group(2)), seconds(*m.group(3, 4, 5))))
        if re.match(r"(rendered back|residual)\s+\[#+\]\s+100%", line) and last_end is None:
            last_end = t
    if last_end is None:
        sys.exit("time_left.py: no render back or residual finished: is this a path-traced analysis?")
    seen = set()
    for t, render, percent, left in said:
        if (render, min(percent // 25, 3)) in seen:
            continue
        seen.add((render, min(percent // 25, 3)))
        print(f"{t:6.1f} s  {render:18s} {percent:3d} %  said {left:4d} s  took {last_end - t:5.1f} s "
              f"(to the exit {exit_time - t:5.1f} s)")


if __name__ == "__main__":
    main(*sys.argv[1:])
