"""The particle tables are the data they say they are: every element's van
der Waals radius and colour as ASE lists them (Alvarez 2013's radii, Jmol's
colours), every colormap's 256 entries as matplotlib lists them."""
import numpy as np
import pytest

from raycast import _raycast

ase_data = pytest.importorskip("ase.data")


def test_every_element_is_aces():
    from ase.data.colors import jmol_colors
    from ase.data.vdw_alvarez import vdw_radii
    for z in range(1, 119):
        symbol = ase_data.chemical_symbols[z]
        assert _raycast.element_symbol(z) == symbol
        radius, colour = _raycast._element_style(symbol)
        want = vdw_radii[z] if z < len(vdw_radii) and not np.isnan(vdw_radii[z]) else 2.0
        assert radius == pytest.approx(want, abs=1e-6), symbol
        if z < len(jmol_colors):
            assert colour == pytest.approx(tuple(jmol_colors[z]), abs=1e-6), symbol
    assert _raycast._element_style("Xx") is None


@pytest.mark.parametrize("name", ["viridis", "magma", "plasma", "inferno", "cividis", "coolwarm"])
def test_every_colormap_entry_is_matplotlibs(name):
    matplotlib = pytest.importorskip("matplotlib")
    cmap = matplotlib.colormaps[name]
    for k in range(256):
        t = (k + 0.5) / 256  # the middle of entry k's span
        assert _raycast._colormap_color(name, t) == pytest.approx(tuple(cmap(k)[:3]), abs=1e-6), (name, k)
