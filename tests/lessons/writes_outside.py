"""A deliberately misbehaving lesson: a hook that writes a file beside
itself and one in the folder named by LIGHTCONE_TEST_OUTSIDE (outside its
own folder): each refused. Its private temporary folder is writable."""

import os
import tempfile
import lightcone


def setup(world):
    scene = lightcone.Scene(title="misbehaves")
    scene.add_puck("a", (0.5, 0.71), beta=(0.5, 0.0))
    world.start(scene)


def on_frame(world, t):
    with tempfile.NamedTemporaryFile("w", suffix=".txt") as f:
        f.write("the scratch folder is writable")
    world.check("its temporary folder is writable", True, tempfile.gettempdir())
    refused = []
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "written_by_a_lesson.txt")
    for path in (here, os.path.join(os.environ["LIGHTCONE_TEST_OUTSIDE"], "written.txt")):
        try:
            with open(path, "w") as f:
                f.write("escaped")
        except PermissionError as e:
            refused.append(f"{path}: {e.strerror}")
    raise PermissionError("writes refused: " + "; ".join(refused))
