import numpy as np
import pytest

from impactlab.materials import BALL_PRESETS


@pytest.fixture
def golf_inputs():
    """Urethane ball on a rigid face at 80 mph; call with overrides (arrays broadcast)."""

    def make(**changes):
        ball = BALL_PRESETS["urethane_tour"]
        base = dict(ball_radius=ball.radius, ball_mass=ball.mass, ball_inertia_factor=ball.inertia_factor,
                    ball_youngs_modulus=ball.material.youngs_modulus, ball_poisson_ratio=ball.material.poisson_ratio,
                    face_youngs_modulus=np.inf, face_poisson_ratio=0.0, friction=0.4, restitution=1.0,
                    speed=35.7632, angle=np.radians(15.0), spin=0.0)
        base.update(changes)
        arrays = {key: np.atleast_1d(np.asarray(value, dtype=float)) for key, value in base.items()}
        n = max(array.size for array in arrays.values())
        return {key: np.broadcast_to(array, (n,)).copy() for key, array in arrays.items()}

    return make
