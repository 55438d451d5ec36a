"""A deliberately broken lesson: setup never returns."""


def setup(world):
    while True:
        pass
