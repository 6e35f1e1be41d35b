"""Typical property values of real engine oils and valvetrain surfaces, with sources.

Every value here is a **typical** value: the middle of a range that published
measurements give for a class of oils or surfaces, not the property of one product. Use
them when nothing better is known; replace them by your own measurements (``tribodyn
calibrate``, docs/guides/calibration.md) when friction matters. The typical engine (cam
sizes, valvetrain masses and spring, elastic constants) is in
:mod:`tribodyn.physics.typical_engine`. The paper's values
(Andreou et al. 2023) stay in :mod:`tribodyn.paper` and in the paper's case files.

Each entry is a :class:`TypicalValue`: value, published range, unit, source, a note on
the conditions and a ``status`` that says how far the source was checked:

* ``"verified"``: the number and its range were found in the cited source's text.
* ``"qualitative"``: the cited source was found and supports the statement in the note
  (for example "close to steel/steel"), but its number was not seen; the value is an
  ASSUMED reading of it.
* ``"assumed"``: no source text giving the number was found; the value is ASSUMED (a
  commonly quoted magnitude). Replace it by a measurement when friction matters.

Citations that were given before but could not be found are named in the note as "not
found". SI units throughout.

Boundary friction in Eq. 17 of the friction law, τ_b = τ₀ A_a/A + ς p_a: a lubricated
boundary test (λ ≪ 1, asperities carry the load) measures the ratio μ_b = F/W of the
*whole* asperity friction to the load. With τ₀ = 0 the law gives F/W = ς exactly when the
asperities carry the load, so a measured boundary coefficient is used as ς with τ₀ = 0
(:data:`BOUNDARY_SHEAR_STRENGTH`). A τ₀ > 0 together with ς = μ_b would count the
film-shear part twice.
"""

from __future__ import annotations

from dataclasses import dataclass

#: the class and functions; the typical values and their tables are appended at the end
__all__ = [
    "TypicalValue",
    "STATUSES",
    "boundary_friction",
    "boundary_friction_range",
    "typical_summits",
]


#: How far the source of a typical value was checked (module text).
STATUSES = ("verified", "qualitative", "assumed")


@dataclass(frozen=True)
class TypicalValue:
    """A typical value with the range it is taken from, the source of both and how far
    that source was checked (``status``: module text)."""

    value: float
    low: float
    high: float
    unit: str
    source: str
    note: str = ""
    status: str = "assumed"

    def __post_init__(self):
        if self.status not in STATUSES:
            raise ValueError(f"status {self.status!r} is not one of {STATUSES}")
        if not self.low <= self.value <= self.high:
            raise ValueError(
                f"typical value {self.value} outside its range [{self.low}, {self.high}]"
            )


def typical_names(namespace: dict) -> list[str]:
    """The public names of ``namespace`` bound to a :class:`TypicalValue` or to a table
    (dict) of them, in definition order (a module's ``__all__``)."""

    def typical(v) -> bool:
        if isinstance(v, dict):
            return bool(v) and all(isinstance(t, TypicalValue) for t in v.values())
        return isinstance(v, TypicalValue)

    return [k for k, v in namespace.items() if not k.startswith("_") and typical(v)]


# ----------------------------------------------------------------------------- oil
#: Dynamic viscosity μ₀ at ambient pressure of an engine oil in a warm engine (≈ 100 °C).
VISCOSITY = TypicalValue(
    0.009,
    0.005,
    0.015,
    "Pa·s",
    "SAE J300, engine oil viscosity classification: kinematic viscosity at 100 °C of the "
    "grades SAE 20 to SAE 40, 6.9–16.3 mm²/s",
    "ASSUMED: the grade limits were not seen in the standard's text here. With ρ ≈ "
    "830 kg/m³ at 100 °C they give μ ≈ 0.006–0.014 Pa·s; 0.009 Pa·s (an SAE 30 grade, "
    "≈ 11 mm²/s) is ASSUMED. A datasheet oil at its inlet temperature (lubricant.oil) "
    "is better.",
    status="assumed",
)
#: Pressure–viscosity coefficient α of engine oils at about 100 °C.
PRESSURE_VISCOSITY = TypicalValue(
    1.5e-8,
    1.0e-8,
    2.5e-8,
    "1/Pa",
    "B. J. Hamrock, S. R. Schmid, B. O. Jacobson, Fundamentals of Fluid Film "
    "Lubrication, 2nd ed., Marcel Dekker, 2004 (pressure–viscosity coefficients of "
    "mineral and synthetic oils)",
    "ASSUMED: α falls with temperature, about 2e-8 1/Pa at 40 °C to 1–1.5e-8 1/Pa at "
    "100 °C; the book's table was not seen here.",
    status="assumed",
)
#: Density ρ₀ of engine oils at ambient pressure.
DENSITY = TypicalValue(
    850.0,
    820.0,
    880.0,
    "kg/m³",
    "engine-oil datasheets: density at 15 °C 0.84–0.87 g/cm³",
    "ASSUMED: the middle of the datasheet range; the density changes the film by far less "
    "than the viscosity.",
    status="assumed",
)


# ----------------------------------------------------------------------------- rheology
#: Eyring stress τ_E of mineral and PAO engine-oil base stocks in EHL traction.
EYRING_STRESS = TypicalValue(
    5e6,
    2e6,
    10e6,
    "Pa",
    "K. L. Johnson, J. L. Tevaarwerk, Shear behaviour of elastohydrodynamic oil films, "
    "Proc. R. Soc. Lond. A 356 (1977) 215-236",
    "ASSUMED: the 2–10 MPa range (τ_E of mineral oils from traction curves, rising with "
    "pressure) and its middle, 5 MPa, were not found in source text here; the citation "
    "(where the Eyring model of EHL traction was fitted) was found. Evans & Johnson, "
    "Proc. IMechE C 200 (1986) 303: not found. The paper's 2 MPa is the low end.",
    status="assumed",
)
#: Pressure slope Λ of the limiting shear stress τ_L = τ_L0 + Λ p.
LIMITING_SHEAR_COEFFICIENT = TypicalValue(
    0.08,
    0.05,
    0.12,
    "-",
    "Investigation of parameters affecting the limiting shear stress-pressure "
    "coefficient: a new model incorporating temperature, J. Tribol. 116 (1994) 612",
    "ASSUMED number: a review text found here gives Λ (disc machine, high-pressure "
    "viscometer and impact tests) 'generally in the range 0.05–0.12', temperature "
    "dependent; the J. Tribol. 116 paper (found) shows Λ depends on oil type, viscosity, "
    "pressure and temperature. Bair & Winer, J. Lubr. Technol. 101 (1979) 258 and "
    "Höglund, Wear 232 (1999) 176: not found.",
    status="qualitative",
)
#: Intercept τ_L0 of the limiting shear stress.
LIMITING_SHEAR_STRESS = TypicalValue(
    0.0,
    0.0,
    5e6,
    "Pa",
    "convention",
    "ASSUMED: 0 keeps τ_L = Λ p, the usual form; measured intercepts are a few MPa.",
    status="assumed",
)

#: The typical value of each ``[lubricant]`` key that has one.
LUBRICANT = {
    "viscosity": VISCOSITY,
    "pressure_viscosity": PRESSURE_VISCOSITY,
    "density": DENSITY,
    "eyring_stress": EYRING_STRESS,
    "limiting_shear_coefficient": LIMITING_SHEAR_COEFFICIENT,
    "limiting_shear_stress": LIMITING_SHEAR_STRESS,
}

# ----------------------------------------------------------------------------- boundary
#: τ₀ of Eq. 17 used with a measured boundary friction coefficient as ς (module text).
BOUNDARY_SHEAR_STRENGTH = TypicalValue(
    0.0,
    0.0,
    0.0,
    "Pa",
    "definition: a lubricated boundary test measures μ_b = F/W = ς when τ₀ = 0",
    "Set τ₀ > 0 only with a ς that excludes it (for example AFM values).",
    status="verified",
)

_ZHANG = (
    "J. Zhang, M. Ueda, S. Campen, H. Spikes, Boundary friction of ZDDP tribofilms, "
    "Tribol. Lett. 69 (2021), issue 1 (MTM, rolling-sliding and pure sliding)"
)
_TUNG = (
    "S. C. Tung, Impacts of molybdenum dithiocarbamate (MoDTC) friction modifier on "
    "tribological performance of fully-formulated GF-3 engine oil, Lubrication "
    "Engineering (Runhua yu Mifeng) 2004 (4), doi:10.3969/j.issn.0254-0150.2004.04.019"
)
_KALIN = (
    "M. Kalin, J. Vižintin, Differences in the tribological mechanisms when using "
    "non-doped, metal-doped (Ti, WC), and non-metal-doped (Si) diamond-like carbon against "
    "steel under boundary lubrication, with and without oil additives, Thin Solid Films "
    "515 (2006) 2734-2747"
)
_NOT_FOUND = (
    "Not found: Graham, Spikes & Korcek, Tribol. Trans. 44 (2001) 626; "
    "Topolovec-Miklozic, Lockwood & Spikes, Wear 265 (2008) 1893; Kalin & Vižintin, "
    "Wear 261 (2006) 22."
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
        status="verified",
    ),
    ("steel", "modtc"): TypicalValue(
        0.05,
        0.03,
        0.07,
        "-",
        _TUNG,
        "MoDTC friction modifier once its MoS₂ film has formed. The source (SRV, "
        "formulated GF-3 oil, nitrided ring on bore) gives a lowest value of 0.03; 0.05 "
        f"is ASSUMED for a steel cam/tappet. {_NOT_FOUND}",
        status="qualitative",
    ),
    ("a-C:H", "zddp"): TypicalValue(
        0.09,
        0.06,
        0.12,
        "-",
        _KALIN,
        "Hydrogenated DLC against steel: the source finds friction similar to steel/steel "
        "for every DLC it tested (paraffinic mineral oil with and without AW/EP "
        "additives); 0.09, a little below steel's 0.115, is ASSUMED. " + _NOT_FOUND,
        status="qualitative",
    ),
    ("a-C:H", "modtc"): TypicalValue(
        0.07,
        0.04,
        0.10,
        "-",
        _PODGORNIK,
        "ASSUMED number. The source finds that antiwear and friction-modifier additives "
        "change DLC friction only a little, so MoDTC lowers friction on a-C:H less than on "
        "steel. " + _NOT_FOUND,
        status="qualitative",
    ),
    ("ta-C", "zddp"): TypicalValue(
        0.07,
        0.05,
        0.10,
        "-",
        _TASDEMIR,
        "ASSUMED number: the source (found; ta-C pin on steel disc, oil temperature and "
        "additive concentration varied) was not read for its friction values. Ester/GMO "
        "oils give far lower values on ta-C (superlow friction); not typical.",
        status="assumed",
    ),
    ("WC-C", "zddp"): TypicalValue(
        0.09,
        0.07,
        0.12,
        "-",
        f"{_PODGORNIK}; {_KALIN}",
        "W-doped a-C:H against steel: similar to steel/steel (Kalin & Vižintin); S-based "
        "EP additives can lower it through WS₂ (Podgornik & Vižintin). The number is "
        "ASSUMED.",
        status="qualitative",
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


#: Key of :data:`BOUNDARY_FRICTION` (surface, ZDDP oil) of each material key of the
#: default ``[materials]`` (config.schema.typical_materials).
MATERIAL_SURFACE = {"steel": "steel", "dlc": "a-C:H", "wcc": "WC-C"}


def boundary_friction_range(material: str | None, value: float) -> tuple[float, float]:
    """(low, high) of a pair's ς around the value ``value`` in use: the published range of
    the typical value of the material (:data:`MATERIAL_SURFACE`, ZDDP oil) scaled by
    ``value``/typical value, so that a ς the case changed keeps the same relative
    spread. A material without a typical entry gets the relative range of steel/ZDDP
    (−22 … +22 %), an ASSUMED spread."""
    key = MATERIAL_SURFACE.get(material or "steel", "steel")
    t = BOUNDARY_FRICTION[(key, "zddp")]
    return value * t.low / t.value, value * t.high / t.value


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
    0.04,
    0.03,
    0.05,
    "-",
    _ARNELL,
    "ASSUMED: the commonly quoted range of ηβσ, nearly independent of the finish; the "
    "cited book and paper were not found.",
    status="assumed",
)
#: σ/β, composite RMS roughness over mean summit radius.
RMS_TO_SUMMIT_RADIUS = TypicalValue(
    1e-3,
    1e-4,
    1e-2,
    "-",
    _ARNELL,
    "ASSUMED (cited sources not found). With σ = 0.2 µm: β = 200 µm, η = ηβσ/(βσ) = 1e9 1/m².",
    status="assumed",
)


def typical_summits(rms: float) -> tuple[float, float]:
    """(η [1/m²], β [m]): the summit density and mean summit radius of a surface of
    composite RMS roughness σ = ``rms`` [m] with the typical ratios above,
    β = σ/(σ/β) (:data:`RMS_TO_SUMMIT_RADIUS`) and η = ηβσ/(βσ)
    (:data:`ROUGHNESS_PARAMETER`). ASSUMED values, as those ratios are."""
    beta = rms / RMS_TO_SUMMIT_RADIUS.value
    return ROUGHNESS_PARAMETER.value / (beta * rms), beta


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
        "Ground cam and ground tappet, R_a ≈ 0.1–0.25 µm each. The measured 0.347–0.408 "
        "µm of Table 4 (tribodyn.paper.ROUGHNESS) lie in the range; 0.3 µm is ASSUMED.",
        status="qualitative",
    ),
    "superfinished": TypicalValue(
        0.08e-6,
        0.04e-6,
        0.15e-6,
        "m",
        "superfinishing/lapping R_a 0.025–0.1 µm (machining finish charts, e.g. ISO 1302 "
        "classes N1–N3)",
        "ASSUMED: superfinished cam and shim, R_a ≈ 0.03–0.08 µm each.",
        status="assumed",
    ),
}


# ----------------------------------------------------------------------------- spectrum
# The default asperity law (``asperity_model = "surface"``) is the boundary-element
# load–separation law of a Gaussian self-affine surface with the set's σ and these
# spectrum parameters (:func:`tribodyn.topography.load_separation.synthetic_load_separation`).
_PERSSON = (
    "B. N. J. Persson, On the fractal dimension of rough surfaces, Tribol. Lett. 54 (2014) 99-106"
)
#: Hurst exponent H of engineering surfaces (fractal dimension D_f = 3 − H).
SURFACE_HURST = TypicalValue(
    0.85,
    0.7,
    1.0,
    "-",
    _PERSSON,
    "The abstract gives D_f = 2.15 ± 0.15 for most natural and engineering surfaces "
    "(polished, sandblasted), i.e. H = 3 − D_f = 0.85 ± 0.15.",
    status="verified",
)
#: Shortest wavelength λ_s of the self-affine spectrum: it sets the RMS slope (with
#: σ = 0.2 µm, H 0.85 and λ_L = 25.6 µm: profile slope √m₂ ≈ 0.06, areal gradient ≈ 0.08).
SURFACE_SHORT_CUTOFF = TypicalValue(
    3.2e-6,
    1.6e-6,
    6.4e-6,
    "m",
    "convention: the shortest wavelength an optical profiler of about 1 µm lateral "
    "resolution resolves (three pixels)",
    "ASSUMED: no published RMS slope of ground cam or tappet steel was found. With "
    "σ = 0.2 µm, H = 0.85 and λ_L = 25.6 µm the value gives an RMS profile slope √m₂ of "
    "0.06 (areal gradient 0.08); Greenwood–Tripp's typical ηβσ = 0.04 and σ/β = 1e-3 "
    "imply √m₂ ≈ 0.02 (Nayak's and McCool's relations). The range halves and doubles "
    "the value. Replace it by a measured map "
    "(measured_surface.topography) when friction matters.",
    status="assumed",
)
#: Longest wavelength λ_L of the self-affine range (the spectrum is flat above it).
SURFACE_LONG_CUTOFF = TypicalValue(
    25.6e-6,
    12.8e-6,
    51.2e-6,
    "m",
    "convention: the roll-off of ground finishes is of the order of the grinding "
    "marks' spacing, tens of µm",
    "ASSUMED: no published roll-off wavelength of ground cam or tappet steel was found; "
    "the range halves and doubles it. The law is computed on a periodic map of side "
    "2 λ_L, so λ_L also sets the map's size.",
    status="assumed",
)


# ----------------------------------------------------------------------------- filter band
# The default band-pass of a measured topography (``tribodyn.topography``, band="auto"):
# the standard roughness cut-offs of a ground or superfinished steel surface.
_ISO_CUTOFFS = (
    "ISO 3274:1996 (λs and stylus tip for each λc) and ISO 4288:1996 (cut-off λc of "
    "non-periodic profiles by R_a), as reproduced in Mitutoyo, Surface Texture and Contour "
    "Measuring Instruments: Explanation of Surface Characteristics and Standards "
    "(leaflet), and in D. J. Whitehouse, Surfaces and their Measurement, Hermes Penton "
    "2002, ch. 3 (table 'Recommended cut-off ISO 4288')"
)
#: Short-wavelength limit λs of the roughness band (the S-filter).
FILTER_SHORT_WAVELENGTH = TypicalValue(
    2.5e-6,
    2.5e-6,
    2.5e-6,
    "m",
    _ISO_CUTOFFS,
    "ISO 3274 gives λs = 2.5 µm for λc = 0.08, 0.25 and 0.8 mm (λc/λs = 30, 100, 300) "
    "and 8 µm only from λc = 2.5 mm (R_a > 2 µm). Read from the leaflet's reproduction "
    "of the tables; the standards' own text and ISO 25178-3's areal nesting indices "
    "were not seen here.",
    status="verified",
)
#: Long-wavelength limit λc of the roughness band (the L-filter), for a ground finish.
FILTER_LONG_WAVELENGTH = TypicalValue(
    0.8e-3,
    0.25e-3,
    0.8e-3,
    "m",
    _ISO_CUTOFFS,
    "ISO 4288 gives λc = 0.25 mm for 0.02 µm < R_a ≤ 0.1 µm (superfinished) and 0.8 mm "
    "for 0.1 µm < R_a ≤ 2 µm (ground cams and tappets, R_a ≈ 0.1–0.4 µm). Read from "
    "reproductions of the table (the 0.8 mm row in a reproduction other than the two "
    "cited); the standard's own text was not seen here. Optical maps of tens of µm are "
    "far smaller: the band is then cut at the field of view.",
    status="verified",
)

__all__ += typical_names(dict(globals()))
