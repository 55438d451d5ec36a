"""A relativistic gas thermalising (the paper's §4.3).

Many pucks start with the same speed in random directions. Collisions share
energy out until the speeds follow the equilibrium distribution of a
two-dimensional relativistic gas, the Jüttner distribution: for the proper
speed u = γβ,

    f(u) du ∝ u · exp(−γ / θ) du,    γ = √(1 + u²),

with θ = kT / (m c²) fixed by the total energy: the mean γ of that
distribution is (1 + 2θ + 2θ²) / (1 + θ). The chart shows the speeds now
(bars) and Jüttner's curve (line).
"""

import math
import random

import lightcone

N_SIDE = (15, 8)  # pucks on a grid: 120
U0 = 1.0  # every puck starts with γβ = 1 (β ≈ 0.71)
BINS = 16
U_MAX = 3.2
SETTLE = 12.0  # board seconds before the distribution is measured
MEASURE = 12.0  # then seconds over which speeds are collected
EVERY = 0.25  # seconds between samples


def theta_for(mean_gamma):
    """The temperature kT/mc² whose Jüttner distribution has this mean γ."""
    g = mean_gamma
    return ((g - 2) + math.sqrt(g * g + 4 * g - 4)) / 4


def cdf(u, theta):
    """Jüttner's cumulative distribution of the proper speed (2-D)."""
    g = math.sqrt(1 + u * u)
    return 1 - math.exp(-(g - 1) / theta) * (g + theta) / (1 + theta)


def ks_distance(samples, theta):
    """Kolmogorov–Smirnov distance between the samples and Jüttner's law."""
    xs = sorted(samples)
    n = len(xs)
    return max(max(abs((i + 1) / n - cdf(x, theta)), abs(i / n - cdf(x, theta))) for i, x in enumerate(xs))


def speeds(world):
    return [math.hypot(*p["u"]) for p in world.state()["pucks"]]


def setup(world):
    rng = random.Random(7)
    scene = lightcone.Scene(title="A relativistic gas")
    nx, ny = N_SIDE
    for i in range(nx):
        for j in range(ny):
            a = rng.uniform(0, 2 * math.pi)
            x = 0.15 + i * (2.84 - 0.3) / (nx - 1)
            y = 0.15 + j * (1.42 - 0.3) / (ny - 1)
            scene.add_puck(f"p{i}_{j}", (x, y), u=(U0 * math.cos(a), U0 * math.sin(a)), radius=0.03)
    world.start(scene)
    world.view = "truth"
    world.time_scale = 2.0
    g = sum(math.sqrt(1 + u * u) for u in speeds(world)) / (nx * ny)
    world.theta = theta_for(g)
    world.energy = g
    world.ks_start = ks_distance(speeds(world), world.theta)
    world.samples = []
    world.next_sample = SETTLE
    world.next_chart = 0.5
    chart(world, speeds(world))  # the start: every puck in one bar
    world.collisions = 0
    world.worst_energy = 0.0
    world.done = False
    world.say(
        f"{nx * ny} pucks start with the same speed (γβ = {U0}) in random directions. "
        f"Their total energy fixes the temperature: kT = {world.theta:.3f} mc²."
    )
    world.ask(
        "After many collisions, will all pucks still have the same speed?",
        ["yes", "no: a spread of speeds, with a few very fast ones"],
        answer=1,
    )


def chart(world, us):
    width = U_MAX / BINS
    edges = [i * width for i in range(BINS + 1)]
    counts = [0] * BINS
    for u in us:
        counts[min(int(u / width), BINS - 1)] += 1
    n = len(us)
    expected = [n * (cdf(edges[i + 1], world.theta) - cdf(edges[i], world.theta)) for i in range(BINS)]
    expected[-1] += n * (1 - cdf(U_MAX, world.theta))
    world.bars("proper speed γβ: pucks (bars), Jüttner (line)", edges, counts, expected)


def on_collision(world, event):
    """Each collision must conserve energy: Σγ before = Σγ after."""
    if event["kind"] != "puck_puck":
        return
    world.collisions += 1
    before = sum(math.sqrt(1 + p["u_before"][0] ** 2 + p["u_before"][1] ** 2) for p in event["pucks"])
    after = sum(math.sqrt(1 + p["u_after"][0] ** 2 + p["u_after"][1] ** 2) for p in event["pucks"])
    world.worst_energy = max(world.worst_energy, abs(after / before - 1))


def on_frame(world, t):
    if world.done:
        return
    if t >= world.next_chart:
        world.next_chart = t + 0.5
        chart(world, speeds(world))
    if t >= world.next_sample:
        world.next_sample += EVERY
        world.samples.extend(speeds(world))
    if t < SETTLE + MEASURE:
        return
    world.done = True
    world.check(
        "every collision conserves energy",
        world.collisions > 1000 and world.worst_energy < 1e-12,
        f"{world.collisions} puck–puck collisions, worst relative change of Σγ {world.worst_energy:.1e}",
    )
    ks = ks_distance(world.samples, world.theta)
    world.check(
        "the speeds settle to the Jüttner distribution",
        ks < 0.05,
        f"Kolmogorov–Smirnov distance {ks:.4f} over {len(world.samples)} speeds "
        f"(at the start {world.ks_start:.3f})",
    )
    chart(world, world.samples)
    world.say(
        f"Over {MEASURE:.0f} s the speeds followed Jüttner's law at kT = {world.theta:.3f} mc² "
        f"(distance {ks:.3f}, from {world.ks_start:.2f} at the start)."
    )
    world.finish("Collisions alone bring the gas to its relativistic equilibrium.")
