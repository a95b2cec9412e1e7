#!/usr/bin/env python3
"""Counts the guest instructions a program runs between two marker functions, under qemu-user.

    python3 scripts/count_instructions.py [--top N] BEGIN END -- QEMU [QEMU OPTIONS] PROGRAM [ARGUMENTS]

Runs the command with qemu's log of translated blocks added (`-d nochain,exec,in_asm`, through a FIFO: a run logs
hundreds of megabytes): each block's instructions once, when qemu translates it ("IN: function", then one line per
instruction), and a "Trace" line each time a block runs (every time, with `nochain`). BEGIN and END name the two
functions around the work counted (apps/warp_run.cpp: rtm_warp_run_begin, rtm_warp_run_end, around each pre-warp).
Prints, one a line, the instructions of every block run from each run of BEGIN to the next run of END (BEGIN's block
counted, END's not); with --top N, then the N functions that ran the most of all of them (qemu's name of each block's
function: inlined code counts in its caller), one a line. The program's standard output is dropped, its errors pass
through. Exits 1 with one line when the command fails, BEGIN and END do not alternate (BEGIN first, at least once),
or a block ran whose instructions the log does not list.

    python3 scripts/count_instructions.py rtm_warp_run_begin rtm_warp_run_end -- \\
        qemu-aarch64 -cpu cortex-a72 build-arm/bin/rtm-warp-run bumps 256 two-pass neon 1
"""
import os
import subprocess
import sys
import tempfile
import threading


def fail(message):
    sys.exit(f"count_instructions: {message}")


def count(log, begin, end, top):
    """([instructions of each BEGIN .. END], [(function, instructions)] of the top functions, None) from the log's
    lines, read to their end; or ([], [], what is wrong)."""
    length = {}  # block address -> instructions
    function = {}  # block address -> qemu's name of its function
    by_function = {}  # name -> instructions counted
    block, name, n = None, None, 0
    counting, seen_begin, seen_end, out_of_turn = False, 0, 0, False
    counts, unknown = [], 0

    def close_block():
        if block is not None:
            length[block] = n
            function[block] = name

    for line in log:
        if line.startswith(b"Trace "):
            close_block()
            block = None
            # Trace 0: 0xHOST [FLAGS/PC/.../...]
            pc = int(line.split(b"/")[1], 16)
            fn = function.get(pc)
            if fn == begin:
                seen_begin += 1
                out_of_turn |= counting
                counting = True
                counts.append(0)
            elif fn == end:
                seen_end += 1
                out_of_turn |= not counting
                counting = False
            if counting:
                c = length.get(pc)
                if c is None:
                    unknown += 1
                else:
                    counts[-1] += c
                    if top:
                        by_function[fn] = by_function.get(fn, 0) + c
        elif line.startswith(b"IN:"):
            close_block()
            block, name, n = None, line[3:].strip(), 0
        elif line.startswith(b"0x"):
            if block is None:
                block = int(line.split(b":")[0], 16)
            n += 1
    if seen_begin == 0 or seen_begin != seen_end or out_of_turn:
        return [], [], (f"{begin.decode()} ran {seen_begin} times and {end.decode()} {seen_end}, "
                        f"{'not in turn' if out_of_turn else 'in turn'} (they must alternate, {begin.decode()} first, "
                        f"at least once; is the program built with its symbols?)")
    if unknown:
        return [], [], f"{unknown} blocks ran whose instructions the log does not list"
    return counts, sorted(by_function.items(), key=lambda fc: -fc[1])[:top], None


def main():
    args = sys.argv[1:]
    top = 0
    if args[:1] == ["--top"]:
        if len(args) < 2 or not args[1].isdigit():
            fail(f"--top: '{args[1] if len(args) > 1 else ''}' is not a whole number")
        top, args = int(args[1]), args[2:]
    if len(args) < 5 or args[2] != "--":
        fail("usage: count_instructions.py [--top N] BEGIN END -- QEMU [QEMU OPTIONS] PROGRAM [ARGUMENTS]")
    begin, end, command = args[0].encode(), args[1].encode(), args[3:]
    with tempfile.TemporaryDirectory() as tmp:
        fifo = os.path.join(tmp, "log")
        os.mkfifo(fifo)
        # Our own writer keeps the FIFO open until qemu has exited, so that a qemu that never opens its log (a bad
        # option, a missing program) ends the read instead of blocking it.
        rfd = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
        wfd = os.open(fifo, os.O_WRONLY)
        os.set_blocking(rfd, True)
        try:
            proc = subprocess.Popen([command[0], "-d", "nochain,exec,in_asm", "-D", fifo] + command[1:],
                                    stdout=subprocess.DEVNULL)
        except OSError as e:
            fail(f"{command[0]}: {e.strerror}")

        def close_writer():
            proc.wait()
            os.close(wfd)

        waiter = threading.Thread(target=close_writer)
        waiter.start()
        with os.fdopen(rfd, "rb") as log:
            counts, functions, error = count(log, begin, end, top)  # reads to the end: qemu never blocks
        waiter.join()
    if proc.returncode != 0:
        fail(f"{' '.join(command)} exited with status {proc.returncode}")
    if error:
        fail(error)
    for c in counts:
        print(c)
    for fn, c in functions:
        print(f"{c:12d} {100.0 * c / sum(counts):5.1f}% {fn.decode(errors='replace') or '?'}")


if __name__ == "__main__":
    main()
