"""The collision angle (the paper's §4.3).

A puck strikes an equal puck at rest, off centre. Without relativity the two
leave at a right angle. Here they leave at less than 90°: for an elastic
collision of equal masses, tan θ₁ · tan θ₂ = 2 / (γ + 1), where γ is the
striker's and θ₁, θ₂ are the two directions measured from its path.

The same shot with light so fast that relativity does not show (c = 10⁶ m/s)
is run beside it, without a window, for comparison.
"""

import math

import lightcone

U = 2.0  # the striker's proper velocity γβ: γ = √5 ≈ 2.24
OFFSET = 0.03  # impact parameter, m (about one radius)


def shot(c=None, u=U):
    scene = lightcone.Scene(c=c, title="The collision angle")
    scene.add_puck("striker", (0.5, 0.71), u=(u, 0.0), color="white")
    scene.add_puck("target", (1.4, 0.71 + OFFSET), color="red")
    return scene


def angles(event):
    """The two outgoing directions from the striker's path, in degrees."""
    out = {p["name"]: p["u_after"] for p in event["pucks"]}
    a1 = math.atan2(out["striker"][1], out["striker"][0])
    a2 = math.atan2(out["target"][1], out["target"][0])
    return abs(math.degrees(a1)), abs(math.degrees(a2))


def setup(world):
    world.start(shot())
    world.view = "truth"
    world.done = False
    # The classical comparison: the same shot at a tiny speed compared to c.
    # β = 10⁻⁶ at 1 m/s: relativistic corrections of order β² are invisible.
    classical = lightcone.Simulation(shot(c=1e6, u=1e-6))
    classical.run_until(5.0)
    first = [e for e in classical.collisions() if e["kind"] == "puck_puck"][0]
    world.classical = angles(first)
    world.say(
        f"The white puck strikes the red one off centre at γ = {math.sqrt(1 + U * U):.2f}. "
        "Without relativity, equal pucks leave a glancing collision at a right angle."
    )
    world.ask(
        "At what angle will they leave each other here?",
        ["exactly 90°", "less than 90°", "more than 90°"],
        answer=1,
    )


def on_collision(world, event):
    if world.done or event["kind"] != "puck_puck":
        return
    world.done = True
    a1, a2 = angles(event)
    gamma = math.sqrt(1 + U * U)
    c1, c2 = world.classical
    world.check(
        "classically the pucks leave at a right angle",
        abs(c1 + c2 - 90.0) < 0.01,
        f"{c1:.3f}° + {c2:.3f}° = {c1 + c2:.3f}°",
    )
    world.check(
        "relativistically the opening angle is less than 90°",
        a1 + a2 < 85.0,
        f"{a1:.3f}° + {a2:.3f}° = {a1 + a2:.3f}°",
    )
    product = math.tan(math.radians(a1)) * math.tan(math.radians(a2))
    world.check(
        "tan θ₁ · tan θ₂ = 2 / (γ + 1)",
        abs(product - 2 / (gamma + 1)) < 1e-6,
        f"{product:.9f} against {2 / (gamma + 1):.9f}",
    )
    world.say(
        f"They leave at {a1 + a2:.1f}° (classically {c1 + c2:.1f}°). "
        "Energy and momentum are both conserved, but energy now includes γ: "
        "the right angle of Newton's billiards is gone."
    )
    # 0.7 s after the answer: closed only once the collision's light has
    # reached the eye, so the student has watched the pucks part.
    world.finish(
        "The faster the striker, the narrower the angle.",
        after_light_from=(event["t"], *event["contact"]),
    )
