"""Cushion reflection (the paper's §4.3).

A fast puck strikes a cushion obliquely. On the table the reflection is a
mirror: the angle out equals the angle in and the speed is unchanged, at
any speed. What the eye sees is another matter: the light from the outgoing
leg and from the incoming leg left the puck at different times, so the seen
path bends where the true one does not.
"""

import math

import lightcone

BETA = (0.55, 0.55)  # |β| ≈ 0.78


def setup(world):
    scene = lightcone.Scene(title="Cushion reflection")
    scene.add_puck("ball", (0.4, 0.35), beta=BETA, color="white")
    scene.add_observer("corner", (-0.6, -0.6, 0.8), look_at=(1.2, 0.8, 0.0))
    world.start(scene)
    world.view = "split"
    world.done = False
    world.say(
        f"A puck at |β| = {math.hypot(*BETA):.2f} strikes the top cushion at 45°. "
        "Left: the table. Right: what the eye sees."
    )
    world.ask(
        "On the table, does it leave the cushion at the angle it came in?",
        ["yes, a mirror", "no, steeper", "no, flatter"],
        answer=0,
    )


def on_collision(world, event):
    if world.done or event["kind"] != "cushion":
        return
    world.done = True
    p = event["pucks"][0]
    (ux, uy), (vx, vy) = p["u_before"], p["u_after"]
    world.check(
        "the cushion reverses only the normal component",
        abs(vx - ux) < 1e-12 and abs(vy + uy) < 1e-12,
        f"u before ({ux:.6f}, {uy:.6f}), after ({vx:.6f}, {vy:.6f})",
    )
    angle_in = math.degrees(math.atan2(abs(ux), abs(uy)))
    angle_out = math.degrees(math.atan2(abs(vx), abs(vy)))
    world.check(
        "the angle of reflection equals the angle of incidence",
        abs(angle_in - angle_out) < 1e-9,
        f"in {angle_in:.9f}°, out {angle_out:.9f}°",
    )
    gamma_in, gamma_out = math.sqrt(1 + ux * ux + uy * uy), math.sqrt(1 + vx * vx + vy * vy)
    world.check(
        "energy (γ) is unchanged",
        abs(gamma_in - gamma_out) < 1e-12,
        f"γ = {gamma_in:.12f} → {gamma_out:.12f}",
    )
    world.say(
        f"In at {angle_in:.2f}°, out at {angle_out:.2f}°: a mirror on the table. "
        "Watch the right-hand picture: the seen path is bent, because the light "
        "from each leg took a different time to arrive."
    )
    # The bounce is seen only when its light reaches the eye: the closing
    # message waits for that.
    bounce = (event["t"], *event["contact"])
    world.finish("Reflection is simple on the table and strange to the eye.", after_light_from=bounce)
