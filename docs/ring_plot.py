"""Draws the ring test of examples/ring_test.rs: python3 docs/ring_plot.py ring.csv out.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
steps = [int(r["step"]) for r in rows]
fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
curves = [
    ("pinned", "pinned wall", "tab:red"),
    ("free", "free edge (held in-plane)", "tab:orange"),
    ("absorbing", "absorbing (quadratic frame, 32 cells)", "tab:blue"),
]
for name, label, colour in curves:
    ax.semilogy(steps, [max(float(r[name]), 1e-9) for r in rows], label=label, color=colour)
ax.set_xlabel("step (dt 0.4)")
ax.set_ylabel("energy in the middle 128 x 128 / bump's energy")
ax.set_title("Ring test: a bump at the centre of a 192 x 192 pool (absorbing frame 32 cells)")
ax.set_ylim(1e-6, 2)
ax.grid(True, which="both", alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[2])
