"""Thomas–Wigner rotation: a puck that nothing twists comes back turned.

A puck bounces round a square box at γ = 10, its velocity turning by 90° at
each cushion. No torque ever acts on it (a cushion pushes through its
centre), yet each turn leaves its rest frame rotated, against the turn, by
the Wigner angle ε of the two boosts:

    tan(|ε|/2) = |u₁ × u′| / ((γ₁ + 1)(γ′ + 1) + u₁·u′)

with u₁ the proper velocity before and u′ the one after, seen from the old
rest frame. After one circuit the velocity is back where it started; the
puck's stripe (its rest-frame +x) is not.
"""

import math

import lightcone

GAMMA = 10.0
U = math.sqrt(GAMMA * GAMMA - 1.0)  # proper speed γβ


def gamma_of(u):
    return math.sqrt(1.0 + u[0] * u[0] + u[1] * u[1])


def seen_from(u1, u2):
    """The proper velocity u2 (board) seen from the rest frame of u1."""
    g1, g2 = gamma_of(u1), gamma_of(u2)
    k = (u1[0] * u2[0] + u1[1] * u2[1]) / (g1 + 1.0) - g2
    return (u2[0] + k * u1[0], u2[1] + k * u1[1])


def wigner_angle(u1, u2):
    """Rotation (rad, counter-clockwise) a torque-free change u1 → u2 adds."""
    up = seen_from(u1, u2)
    cross = u1[0] * up[1] - u1[1] * up[0]
    dot = u1[0] * up[0] + u1[1] * up[1]
    return -2.0 * math.atan2(cross, (gamma_of(u1) + 1.0) * (gamma_of(up) + 1.0) + dot)


def setup(world):
    scene = lightcone.Scene(size=(1.0, 1.0), c=1.0, title="Thomas–Wigner rotation")
    s = U / math.sqrt(2.0)
    scene.add_puck("spinner", (0.31, 0.47), u=(s, s), color="white")
    world.start(scene)
    world.time_scale = 0.25
    world.expected = 0.0
    world.bounces = 0
    world.start_u = (s, s)
    world.done = False
    world.say(
        f"A puck at γ = {GAMMA:.0f} bounces round a square box; each cushion turns its "
        "velocity by 90°. Watch the dark stripe on its side (its rest-frame +x)."
    )
    world.ask(
        "After one circuit its velocity is back where it started. Its stripe is ...",
        ["back where it started", "turned, though nothing twisted it"],
        answer=1,
    )


def on_collision(world, event):
    if world.done or event["kind"] != "cushion":
        return
    p = event["pucks"][0]
    world.bounces += 1
    world.expected += wigner_angle(p["u_before"], p["u_after"])
    if world.bounces < 4:
        world.check(
            f"bounce {world.bounces}: the rest frame turned by the Wigner angle",
            abs(p["orientation"] - world.expected) < 1e-9,
            f"orientation {math.degrees(p['orientation']):.6f}°, "
            f"closed form {math.degrees(world.expected):.6f}°",
        )
        return
    world.done = True
    back = math.hypot(p["u_after"][0] - world.start_u[0], p["u_after"][1] - world.start_u[1])
    world.check(
        "after a circuit the velocity is back",
        back < 1e-9 * U,
        f"|u − u₀| = {back:.2e}",
    )
    world.check(
        "and the rest frame is turned by four Wigner angles",
        abs(p["orientation"] - world.expected) < 1e-9 and abs(world.expected) > 1.0,
        f"orientation {math.degrees(p['orientation']):.4f}°, "
        f"4 × ε = {math.degrees(world.expected):.4f}°",
    )
    per = math.degrees(world.expected) / 4.0
    world.say(
        f"Each 90° turn at γ = {GAMMA:.0f} rotated the rest frame by {per:.2f}°, against "
        "the turn: two boosts in different directions make a boost and a rotation. "
        "Slow pucks turn by about u²/2 per bounce, too little to see."
    )
    # Closed once the eye has seen the fourth bounce (its light takes a
    # second or more at c = 1 m/s).
    world.finish(
        "No torque, yet the puck comes back rotated: Thomas–Wigner rotation.",
        after_light_from=(event["t"], *event["contact"]),
    )
