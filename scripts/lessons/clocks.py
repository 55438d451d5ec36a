"""Time dilation, with clocks (the paper's §4.3).

Three pucks carry clocks: one rests, two move at β = 0.6 and 0.8. On the
table a moving clock runs slow by 1/γ. What the eye sees is different
again: the light from an approaching clock arrives ever sooner, so it is
seen to run fast, by the Doppler factor D = 1 / (γ (1 − β·n)).
"""

import math

import lightcone

LANES = {"resting": (0.0, 0.30), "β = 0.6": (0.6, 0.71), "β = 0.8": (0.8, 1.12)}
EYE = (3.4, 0.71, 0.3)  # ahead of the movers, beyond the right cushion


def setup(world):
    scene = lightcone.Scene(title="Clocks")
    for i, (name, (beta, y)) in enumerate(LANES.items()):
        scene.add_puck(name, (0.3, y), beta=(beta, 0.0), color=["white", "yellow", "red"][i])
    scene.add_observer("ahead", EYE, look_at=(1.0, 0.71, 0.0))
    world.start(scene)
    world.observer = "ahead"
    world.done = False
    world.say(
        "Each puck shows its own clock (its proper time). They all read 0 at t = 0 "
        "on the table. Watch them as they come towards you."
    )
    world.ask(
        "Which clock do you SEE running fastest?",
        ["the resting one", "β = 0.6", "β = 0.8"],
        answer=2,
    )


def gamma_of(beta):
    return 1 / math.sqrt((1 - beta) * (1 + beta))


def on_frame(world, t):
    if world.done or t < 2.5:
        return
    world.done = True
    state = {p["name"]: p for p in world.state()["pucks"]}
    lines, ok = [], True
    for name, (beta, _) in LANES.items():
        tau, expect = state[name]["proper_time"], t / gamma_of(beta)
        ok = ok and abs(tau - expect) < 1e-9 * max(1.0, t)
        lines.append(f"{name}: τ = {tau:.6f} s, t/γ = {expect:.6f} s")
    world.check("on the table each clock reads t/γ", ok, "; ".join(lines))

    # Seen rates: how fast each seen clock advances per second of the eye,
    # at a moment when the light from every puck left it after t = 0 and
    # before any bounce (so it is the puck on the table that is seen).
    h, t_obs = 1e-3, 2.4
    a = {p["name"]: p for p in world.observe(t=t_obs - h)["pucks"]}
    b = {p["name"]: p for p in world.observe(t=t_obs + h)["pucks"]}
    lines, ok, rates = [], True, {}
    for name, (beta, _) in LANES.items():
        rate = (b[name]["seen_proper_time"] - a[name]["seen_proper_time"]) / (2 * h)
        pa, pb = a[name]["emission"]["position"], b[name]["emission"]["position"]
        p = [(pa[i] + pb[i]) / 2 for i in range(3)]
        n = [EYE[i] - p[i] for i in range(3)]
        cos = n[0] / math.sqrt(sum(x * x for x in n))
        doppler = 1 / (gamma_of(beta) * (1 - beta * cos))
        emitted = a[name]["emission"]["t"]
        ok = ok and abs(rate / doppler - 1) < 1e-4 and 0.0 < emitted < 2.2
        rates[name] = rate
        lines.append(f"{name}: seen rate {rate:.4f}, D = {doppler:.4f} (light left at t = {emitted:.3f} s)")
    world.check("the seen clocks run at the Doppler factor D", ok, "; ".join(lines))
    world.check(
        "approaching, the fastest mover's clock is seen to run fastest",
        rates["β = 0.8"] > rates["β = 0.6"] > rates["resting"],
        ", ".join(f"{k} {v:.3f}" for k, v in rates.items()),
    )
    world.say(
        "On the table, moving clocks run slow (τ = t/γ). Seen coming towards you, "
        "they run fast: the Doppler factor wins over time dilation."
    )
    world.finish("Dilation is what clocks do; Doppler is how you see them.")
