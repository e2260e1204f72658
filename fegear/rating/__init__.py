"""Rating for a life: a load spectrum's levels against a material's S-N lines by Miner's rule
(docs/rating.md).

The stage is pure arithmetic on stresses the tooth-pair solve gives: the life factors of ISO
6336-2/-3 (:mod:`.life`), the materials and their sources (:mod:`.materials`), Miner's sum and
the safety factor at a required life (:mod:`.miner`), the spectrum files (:mod:`.spectrum`) and
a pair's four modes rated (:mod:`.modes`).

>>> from fegear.rating import BENDING, damage, material
>>> steel = material("42CrMo")
>>> curve = BENDING[steel.treatment]             # Y_NT: 2.5 up to 10^4 cycles, 1 from 3·10^6
>>> round(curve.factor(1e5), 3), round(curve.exponent, 2)
(1.727, 6.22)
>>> round(damage([1.2 * steel.sigma_FE], [1e6], steel.sigma_FE, curve), 3)
1.037
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "life": ("LifeCurve", "BENDING", "CONTACT", "TREATMENTS"),
    "materials": ("GearMaterial", "MATERIALS", "material"),
    "miner": ("damage", "safety_at_life"),
    "spectrum": ("LoadLevel", "Spectrum", "read_spectrum"),
    "modes": ("MODES", "rate", "verdict"),
})
