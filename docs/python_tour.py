"""A tour of `import lightcone`, as a script (or paste it into Jupyter cell
by cell: a `Simulation` and a rendered `Frame` show inline there).

    python3 docs/python_tour.py [OUT_DIR]

Builds a head-on scene, runs it, plots each puck's worldline x(t) and its
Lorentz factor γ(t) with matplotlib, and renders what the observer sees.
Writes `tour_worldlines.png` and `tour_frame.png` to OUT_DIR (default: .).
The test suite runs it (tests/python/test_docs.py) when matplotlib is
installed.
"""

import math
import os
import sys

import lightcone

out = sys.argv[1] if len(sys.argv) > 1 else "."

# A puck at 0.8 c strikes one at rest; light crosses the table in 2 s.
scene = lightcone.Scene(size=(4.0, 2.0), c=2.0, title="head-on")
scene.add_puck("a", (1.0, 1.0), beta=(0.8, 0.0))
scene.add_puck("b", (3.0, 1.0))
scene.add_observer("side", (2.0, -1.5, 1.0))
sim = lightcone.Simulation(scene)

# Sample the board-frame state every 10 ms of board time.
times, xs, gammas = [], {"a": [], "b": []}, {"a": [], "b": []}
for i in range(301):
    sim.run_until(i * 0.01)
    state = sim.state()
    times.append(state["t"])
    for p in state["pucks"]:
        ux, uy = p["u"]
        xs[p["name"]].append(p["position"][0])
        gammas[p["name"]].append(math.sqrt(1.0 + ux * ux + uy * uy))

for c in sim.collisions():
    print(c["kind"], "at t =", round(c["t"], 4), "s:", [p["name"] for p in c["pucks"]])

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed: no plot")
else:
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
    for name in xs:
        ax1.plot(xs[name], times, label=name)
        ax2.plot(times, gammas[name], label=name)
    ax1.set_xlabel("x (m)")
    ax1.set_ylabel("board time t (s)")
    ax1.set_title("worldlines")
    ax2.set_xlabel("board time t (s)")
    ax2.set_ylabel("γ")
    ax2.set_title("Lorentz factor")
    ax1.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tour_worldlines.png"), dpi=80)

try:
    frame = sim.render(size=(480, 270), at=1.5)
except lightcone.NoAdapterError as e:
    print("no frame:", e)
else:
    frame.save(os.path.join(out, "tour_frame.png"))
    print(frame)
