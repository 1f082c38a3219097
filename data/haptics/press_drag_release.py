#!/usr/bin/env python3
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
"""Writes press_drag_release.csv: a device path over the default scene's liver, sampled at 100 Hz,
as a hand would move the probe: press 1.5 cm down over the tumour, drag 4 cm across, lift off.
Each move eases in and out (a cosine), so the velocity has no jumps. Units: seconds, metres."""

import math

# (duration [s], end position [m]) after the start; the tip points down (+z is the tool's axis)
START = (0.010, 0.0, 0.085)
MOVES = [
    (0.3, (0.010, 0.0, 0.085)),  # hold above the surface
    (1.2, (0.010, 0.0, 0.058)),  # press: 2.7 cm down, through the surface at about 7.3 cm
    (0.3, (0.010, 0.0, 0.058)),  # hold
    (2.0, (0.050, 0.0, 0.060)),  # drag 4 cm across at 2 cm/s on average
    (0.3, (0.050, 0.0, 0.060)),  # hold
    (0.6, (0.050, 0.0, 0.085)),  # lift off
    (0.3, (0.050, 0.0, 0.085)),  # hold above
]
RATE = 100.0  # samples per second


def main():
    rows = ["time_s,x_m,y_m,z_m,qw,qx,qy,qz"]
    t0, here = 0.0, START
    rows.append("%.3f,%.6f,%.6f,%.6f,1,0,0,0" % ((t0,) + here))
    for duration, there in MOVES:
        steps = int(round(duration * RATE))
        for i in range(1, steps + 1):
            s = 0.5 - 0.5 * math.cos(math.pi * i / steps)
            p = tuple(a + s * (b - a) for a, b in zip(here, there))
            rows.append("%.3f,%.6f,%.6f,%.6f,1,0,0,0" % ((t0 + i / RATE,) + p))
        t0 += steps / RATE
        here = there
    with open("press_drag_release.csv", "w") as out:
        out.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
