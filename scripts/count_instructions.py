#!/usr/bin/env python3
"""Counts the guest instructions a program ran between two marker functions, from qemu-user's log.

    python3 scripts/count_instructions.py LOG BEGIN END [TOP]

LOG is what `qemu-<arch> -d nochain,exec,in_asm -D LOG` wrote (a file or a FIFO): each translated block's
instructions once ("IN: function" and one line per instruction, when qemu translates it), and a "Trace" line each
time a block runs (every time, with `nochain`). BEGIN and END name the two functions around the work counted
(apps/warp_run.cpp: rtm_warp_run_begin, rtm_warp_run_end). Prints the instructions of every block run from BEGIN's
first block to END's, inclusive of BEGIN's and exclusive of END's; with TOP, then the TOP functions that ran the most
of them (qemu's name of each block's function: inlined code counts in its caller's), one a line. Exits 1 with one line when a marker never runs,
runs more than once, or a block ran whose instructions the log does not list.
"""
import sys


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit("usage: count_instructions.py LOG BEGIN END [TOP]")
    log, begin, end = sys.argv[1], sys.argv[2].encode(), sys.argv[3].encode()
    top = sys.argv[4] if len(sys.argv) == 5 else "0"
    if not top.isdigit():
        sys.exit(f"count_instructions: TOP '{top}' is not a whole number")
    top = int(top)
    length = {}  # block address -> instructions
    function = {}  # block address -> qemu's name of its function
    by_function = {}  # name -> instructions counted
    marker = {}  # block address -> b"begin" / b"end"
    block, name, n = None, None, 0
    counting, seen_begin, seen_end = False, 0, 0
    total, unknown = 0, 0

    def close_block():
        if block is not None:
            length[block] = n
            function[block] = name
            if name == begin:
                marker[block] = b"begin"
            elif name == end:
                marker[block] = b"end"

    with open(log, "rb") as f:
        for line in f:
            if line.startswith(b"Trace "):
                close_block()
                block = None
                # Trace 0: 0xHOST [FLAGS/PC/.../...]
                pc = int(line.split(b"/")[1], 16)
                m = marker.get(pc)
                if m == b"begin":
                    seen_begin += 1
                    counting = True
                elif m == b"end":
                    seen_end += 1
                    counting = False
                if counting:
                    c = length.get(pc)
                    if c is None:
                        unknown += 1
                    else:
                        total += c
                        if top:
                            fn = function[pc]
                            by_function[fn] = by_function.get(fn, 0) + c
            elif line.startswith(b"IN:"):
                close_block()
                block, name, n = None, line[3:].strip(), 0
            elif line.startswith(b"0x"):
                if block is None:
                    block = int(line.split(b":")[0], 16)
                n += 1
    if seen_begin != 1 or seen_end != 1:
        sys.exit(f"count_instructions: {log}: {begin.decode()} ran {seen_begin} times and {end.decode()} "
                 f"{seen_end} (each must run once; is the program built with its symbols?)")
    if unknown:
        sys.exit(f"count_instructions: {log}: {unknown} blocks ran whose instructions the log does not list")
    print(total)
    for fn, c in sorted(by_function.items(), key=lambda fc: -fc[1])[:top]:
        print(f"{c:12d} {100.0 * c / total:5.1f}% {fn.decode(errors='replace') or '?'}")


if __name__ == "__main__":
    main()
