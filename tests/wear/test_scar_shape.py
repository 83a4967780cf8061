"""fewear.wear.scar.scar_shape: a U (gross slip, deepest in the middle) or a W (partial slip,
the stick zone in the middle unworn) on synthetic profiles."""

import numpy as np

from fewear.wear.scar import scar_shape


def test_u_and_w():
    x = np.linspace(-1.0, 1.0, 401)
    u = np.clip(1.0 - x**2 / 0.25, 0.0, None)  # a parabola over |x| < 0.5
    w = u * (1.0 - 0.8 * np.exp(-(x / 0.1) ** 2))  # its middle 80 % shallower
    assert scar_shape(x, u) == "U"
    assert scar_shape(x, w) == "W"
    # a U off centre is still a U: the middle is half way between the scar's edges
    assert scar_shape(x, np.interp(x - 0.3, x, u)) == "U"
