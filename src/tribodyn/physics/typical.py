"""Typical property values of real engine oils and valvetrain surfaces, with sources.

Every value here is a **typical** value: the middle of a range that published
measurements give for a class of oils or surfaces, not the property of one product. Use
them when nothing better is known; replace them by your own measurements (``tribodyn
calibrate``, docs/guides/calibration.md) when friction matters. The paper's values
(Andreou et al. 2023) stay in :mod:`tribodyn.paper` and in the paper's case files.

Each entry is a :class:`TypicalValue`: value, published range, unit, source, and a note
on the conditions. SI units throughout.

Boundary friction in Eq. 17 of the friction law, τ_b = τ₀ A_a/A + ς p_a: a lubricated
boundary test (λ ≪ 1, asperities carry the load) measures the ratio μ_b = F/W of the
*whole* asperity friction to the load. With τ₀ = 0 the law gives F/W = ς exactly when the
asperities carry the load, so a measured boundary coefficient is used as ς with τ₀ = 0
(:data:`BOUNDARY_SHEAR_STRENGTH`). A τ₀ > 0 together with ς = μ_b would count the
film-shear part twice.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "TypicalValue",
    "EYRING_STRESS",
    "LIMITING_SHEAR_COEFFICIENT",
    "LIMITING_SHEAR_STRESS",
    "BOUNDARY_SHEAR_STRENGTH",
    "BOUNDARY_FRICTION",
    "ROUGHNESS_PARAMETER",
    "RMS_TO_SUMMIT_RADIUS",
    "COMPOSITE_RMS",
    "boundary_friction",
]


@dataclass(frozen=True)
class TypicalValue:
    """A typical value with the range it is taken from and the source of both."""

    value: float
    low: float
    high: float
    unit: str
    source: str
    note: str = ""

    def __post_init__(self):
        if not self.low <= self.value <= self.high:
            raise ValueError(
                f"typical value {self.value} outside its range [{self.low}, {self.high}]"
            )


# ----------------------------------------------------------------------------- rheology
#: Eyring stress τ_E of mineral and PAO engine-oil base stocks in EHL traction.
EYRING_STRESS = TypicalValue(
    5e6,
    2e6,
    10e6,
    "Pa",
    "K. L. Johnson, J. L. Tevaarwerk, Shear behaviour of elastohydrodynamic oil films, "
    "Proc. R. Soc. Lond. A 356 (1977) 215-236; C. R. Evans, K. L. Johnson, The rheological "
    "properties of elastohydrodynamic lubricants, Proc. IMechE C 200 (1986) 303-312",
    "τ_E of mineral oils from traction curves lies between about 2 and 10 MPa and rises "
    "with pressure; 5 MPa is the middle of that range, not a fit to any one oil. The "
    "paper's 2 MPa is the low end.",
)
#: Pressure slope Λ of the limiting shear stress τ_L = τ_L0 + Λ p.
LIMITING_SHEAR_COEFFICIENT = TypicalValue(
    0.08,
    0.04,
    0.11,
    "-",
    "S. Bair, W. O. Winer, A rheological model for elastohydrodynamic contacts based on "
    "primary laboratory data, J. Lubr. Technol. 101 (1979) 258-265; E. Höglund, "
    "Influence of lubricant properties on elastohydrodynamic lubrication, Wear 232 "
    "(1999) 176-184",
    "Λ of mineral and synthetic oils measured in high-pressure shear and traction; it "
    "falls with temperature (Höglund).",
)
#: Intercept τ_L0 of the limiting shear stress.
LIMITING_SHEAR_STRESS = TypicalValue(
    0.0,
    0.0,
    5e6,
    "Pa",
    "Bair & Winer (1979), as above",
    "A few MPa at most; 0 keeps τ_L = Λ p, the usual form.",
)

# ----------------------------------------------------------------------------- boundary
#: τ₀ of Eq. 17 used with a measured boundary friction coefficient as ς (module text).
BOUNDARY_SHEAR_STRENGTH = TypicalValue(
    0.0,
    0.0,
    0.0,
    "Pa",
    "definition: a lubricated boundary test measures μ_b = F/W = ς when τ₀ = 0",
    "Set τ₀ > 0 only with a ς that excludes it (for example AFM values).",
)

_ZHANG = (
    "J. Zhang, M. Ueda, S. Campen, H. Spikes, Boundary friction of ZDDP tribofilms, "
    "Tribol. Lett. 69 (2021), issue 1 (MTM rolling-sliding and pure sliding, 100 °C)"
)
_GRAHAM = (
    "J. Graham, H. Spikes, S. Korcek, The friction reducing properties of molybdenum "
    "dialkyldithiocarbamate additives: Part I, Tribol. Trans. 44 (2001) 626-636"
)
_TOPOLOVEC = (
    "T. Topolovec-Miklozic, F. Lockwood, H. Spikes, Behaviour of boundary lubricating "
    "additives on DLC coatings, Wear 265 (2008) 1893-1901"
)
_KALIN = (
    "M. Kalin, J. Vižintin, A comparison of the tribological behaviour of steel/steel, "
    "steel/DLC and DLC/DLC contacts when lubricated with mineral and biodegradable oils, "
    "Wear 261 (2006) 22-31"
)
_TASDEMIR = (
    "H. A. Tasdemir et al., The effect of oil temperature and additive concentration on "
    "the wear of non-hydrogenated DLC coating, Tribol. Int. 77 (2014) 65-71"
)
_PODGORNIK = (
    "B. Podgornik, J. Vižintin, Action of oil additives when used in DLC coated contacts, "
    "Tribol. Mater. Surf. Interfaces 4 (2010) 186-190"
)

#: Boundary friction coefficient μ_b (used as ς with τ₀ = 0) of a surface pair against
#: steel in a formulated oil, by (surface, additive). Lubricated boundary tests
#: (λ ≪ 1), 80–100 °C.
BOUNDARY_FRICTION: dict[tuple[str, str], TypicalValue] = {
    ("steel", "zddp"): TypicalValue(
        0.115,
        0.09,
        0.14,
        "-",
        _ZHANG,
        "ZDDP tribofilm on steel; 0.09–0.14 with alkyl structure, secondary ZDDPs ≈ 0.115.",
    ),
    ("steel", "modtc"): TypicalValue(
        0.05, 0.04, 0.07, "-", _GRAHAM, "MoDTC friction modifier once its MoS₂ film has formed."
    ),
    ("a-C:H", "zddp"): TypicalValue(
        0.09,
        0.06,
        0.12,
        "-",
        f"{_TOPOLOVEC}; {_KALIN}",
        "Hydrogenated DLC against steel: close to steel/steel in ZDDP oils, no large gain.",
    ),
    ("a-C:H", "modtc"): TypicalValue(
        0.07,
        0.04,
        0.10,
        "-",
        _TOPOLOVEC,
        "MoDTC lowers friction on a-C:H less than on steel (and wears it).",
    ),
    ("ta-C", "zddp"): TypicalValue(
        0.07,
        0.05,
        0.10,
        "-",
        _TASDEMIR,
        "Non-hydrogenated ta-C pin against steel, formulated/ZDDP oils, 80–100 °C. "
        "Ester/GMO oils give far lower values on ta-C (superlow friction); not typical.",
    ),
    ("WC-C", "zddp"): TypicalValue(
        0.09,
        0.07,
        0.12,
        "-",
        f"{_PODGORNIK}; {_KALIN}",
        "W-doped a-C:H against steel; S-based EP additives can lower it (WS₂).",
    ),
}


def boundary_friction(surface: str, additive: str = "zddp") -> TypicalValue:
    """Typical boundary friction coefficient of ``surface`` against steel in an oil whose
    boundary additive is ``additive`` (keys of :data:`BOUNDARY_FRICTION`)."""
    from .._validation import InputError

    try:
        return BOUNDARY_FRICTION[(surface, additive.lower())]
    except KeyError:
        known = ", ".join(f"{s}/{a}" for s, a in BOUNDARY_FRICTION)
        raise InputError(
            f"no typical boundary friction for surface {surface!r} in a {additive!r} oil "
            f"(known: {known})"
        ) from None


# ----------------------------------------------------------------------------- roughness
_ARNELL = (
    "R. D. Arnell, P. B. Davies, J. Halling, T. L. Whomes, Tribology: Principles and "
    "Design Applications, Macmillan, 1991 (Greenwood–Tripp parameters of engineering "
    "surfaces), as used for cam–tappet contacts by P. Teodorescu, S. Kushwaha, H. "
    "Rahnejat, D. Taylor, Elastodynamic transient analysis of a four-cylinder valvetrain "
    "system with camshaft flexibility, Proc. IMechE K 217 (2003)"
)
#: ηβσ of ground and superfinished steel surfaces.
ROUGHNESS_PARAMETER = TypicalValue(
    0.04, 0.03, 0.05, "-", _ARNELL, "Nearly independent of the finishing process."
)
#: σ/β, composite RMS roughness over mean summit radius.
RMS_TO_SUMMIT_RADIUS = TypicalValue(
    1e-3,
    1e-4,
    1e-2,
    "-",
    _ARNELL,
    "With σ = 0.2 µm, β = 200 µm and η = ηβσ/(βσ) = 1e9 1/m².",
)
#: Composite RMS roughness σ of a cam against a flat tappet, by finish of the tappet.
#: σ ≈ 1.25 R_a for a Gaussian profile; composite σ = √(σ_cam² + σ_tappet²).
COMPOSITE_RMS: dict[str, TypicalValue] = {
    "ground": TypicalValue(
        0.3e-6,
        0.15e-6,
        0.45e-6,
        "m",
        "Andreou et al. (2023) Table 4: 0.35–0.41 µm measured on ground tappets; "
        "ground finishes R_a 0.1–0.4 µm (machining finish charts, e.g. ISO 1302 classes)",
        "Ground cam and ground tappet, R_a ≈ 0.1–0.25 µm each.",
    ),
    "superfinished": TypicalValue(
        0.08e-6,
        0.04e-6,
        0.15e-6,
        "m",
        "superfinishing/lapping R_a 0.025–0.1 µm (machining finish charts, e.g. ISO 1302 "
        "classes N1–N3)",
        "Superfinished cam and shim, R_a ≈ 0.03–0.08 µm each.",
    ),
}
