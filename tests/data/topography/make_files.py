"""Write the instrument files of this folder from the formats' published layouts.

Every file holds the same rough surface (or a profile of it), written byte by byte with
``struct``/``numpy`` from the format's public description (see README.md), not with
SurfaceTopography's writers. The surface and the dropout pattern come from
:func:`surface` and :func:`dropouts`, so tests can compare what is read with what was
written, point by point.

Run ``python tests/data/topography/make_files.py`` to regenerate the files; the output is
deterministic.
"""

from __future__ import annotations

import hashlib
import io
import struct
import zipfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent

#: grid of the areal files: NX points along x (the fast axis of every format), NY lines
NX, NY = 160, 120
#: pixel size [m] (square pixels)
DX = 0.5e-6
#: RMS roughness of the rough part [m]
SIGMA = 0.3e-6
#: spectrum of the rough part: wavelengths 4–30 µm
SHORT, LONG = 4e-6, 30e-6
#: a plane z = TILT_X x + TILT_Y y: shows flips and transpositions of the axes
TILT_X, TILT_Y = 2e-3, -1e-3
#: profile: points and spacing [m]
NP, DXP = 2000, 0.25e-6


def _rough(shape, dx, seed) -> np.ndarray:
    """Isotropic Gaussian rough surface, wavelengths SHORT–LONG, RMS SIGMA (periodic)."""
    rng = np.random.default_rng(seed)
    noise = rng.standard_normal(shape)
    qx = 2 * np.pi * np.fft.fftfreq(shape[0], dx)
    qy = 2 * np.pi * np.fft.rfftfreq(shape[1], dx) if len(shape) == 2 else None
    q = np.abs(qx) if qy is None else np.hypot(qx[:, None], qy[None, :])
    keep = (q >= 2 * np.pi / LONG) & (q <= 2 * np.pi / SHORT)
    if qy is None:
        h = np.fft.ifft(np.fft.fft(noise) * keep).real
    else:
        h = np.fft.irfft2(np.fft.rfft2(noise) * keep, s=shape)
    return h * (SIGMA / h.std())


def surface() -> np.ndarray:
    """Heights [m] as an (NX, NY) array: index [ix, iy] is the point at x = ix·DX,
    y = iy·DX (y upward). Rough part plus the tilt plane."""
    h = _rough((NX, NY), DX, seed=2024)
    x = np.arange(NX)[:, None] * DX
    y = np.arange(NY)[None, :] * DX
    return h + TILT_X * x + TILT_Y * y


def dropouts() -> np.ndarray:
    """(NX, NY) mask of points the instrument did not measure: ≈ 28 %, as on optical
    profilers (clusters on steep flanks plus scattered single pixels)."""
    rng = np.random.default_rng(7)
    from scipy.ndimage import gaussian_filter

    blobs = gaussian_filter(rng.standard_normal((NX, NY)), 4.0, mode="wrap")
    mask = blobs > np.quantile(blobs, 0.80)
    mask |= rng.random((NX, NY)) < 0.10
    return mask


def profile() -> np.ndarray:
    """Profile heights [m], NP points DXP apart, with a tilt, no dropouts."""
    h = _rough((NP,), DXP, seed=99)
    return h + TILT_X * np.arange(NP) * DXP


def profile_dropouts() -> np.ndarray:
    rng = np.random.default_rng(11)
    return rng.random(NP) < 0.05


def rows_top_down(a: np.ndarray) -> np.ndarray:
    """(NY, NX) image rows, row 0 at the top (largest y): the order of camera formats."""
    return a.T[::-1]


def rows_bottom_up(a: np.ndarray) -> np.ndarray:
    """(NY, NX) rows, row 0 at y = 0."""
    return a.T


# ----------------------------------------------------------------------------- ISO 25178-72
def write_x3p(path: Path, h: np.ndarray, mask: np.ndarray) -> None:
    """ISO 25178-72 (ISO 5436-2) XML 3D surface profile: a zip with main.xml,
    bindata/data.bin (float32 heights in m, x fastest, invalid points NaN) and
    md5checksum.hex."""
    z = np.where(mask, np.nan, h).astype("<f4")
    data = rows_bottom_up(z).tobytes()
    xml = f"""<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:schemaLocation="http://www.opengps.eu/2008/ISO5436_2 http://www.opengps.eu/2008/ISO5436_2/ISO5436_2.xsd">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{DX:.10E}</Increment><Offset>0.0</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{DX:.10E}</Increment><Offset>0.0</Offset></CY>
      <CZ><AxisType>A</AxisType><DataType>F</DataType></CZ>
    </Axes>
  </Record1>
  <Record2>
    <Date>2024-05-06T10:11:12.0+02:00</Date>
    <Instrument><Manufacturer>tribodyn test data</Manufacturer><Model>synthetic</Model><Serial>0</Serial><Version>1</Version></Instrument>
    <CalibrationDate>2024-01-01T00:00:00.0+01:00</CalibrationDate>
    <ProbingSystem><Type>NonContacting</Type><Identification>white-light interferometer</Identification></ProbingSystem>
    <Comment>written from the published layout; 28 % invalid points (NaN)</Comment>
  </Record2>
  <Record3>
    <MatrixDimension><SizeX>{NX}</SizeX><SizeY>{NY}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
    <DataLink><PointDataLink>bindata/data.bin</PointDataLink><MD5ChecksumPointData>{hashlib.md5(data).hexdigest().upper()}</MD5ChecksumPointData></DataLink>
  </Record3>
  <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>
""".encode()
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.writestr("main.xml", xml)
        zf.writestr("bindata/data.bin", data)
        zf.writestr("md5checksum.hex", f"{hashlib.md5(xml).hexdigest().upper()} *main.xml\n")
    path.write_bytes(buf.getvalue())


# ----------------------------------------------------------------------------- ISO 25178-71
def write_sdf(path: Path, h: np.ndarray, mask: np.ndarray) -> None:
    """ISO 25178-71 surface data file, ASCII variant ("aISO-1.0"): header lines
    ``Key = value``, ``*``, heights (DataType 7, double) × Zscale in m, profile after
    profile (x fastest), invalid points ``BAD``, closing ``*``."""
    ny = h.shape[1]
    lines = [
        "aISO-1.0",
        "ManufacID   = tribodyn",
        "CreateDate  = 060520241011",
        "ModDate     = 060520241011",
        f"NumPoints   = {h.shape[0]}",
        f"NumProfiles = {ny}",
        f"Xscale      = {DX if ny > 1 else DXP:.6E}",
        f"Yscale      = {DX:.6E}",
        "Zscale      = 1.0E-06",
        "Zresolution = -1",
        "Compression = 0",
        "DataType    = 7",
        "CheckType   = 0",
        "NumDataSet  = 1",
        f"NanPresent  = {1 if mask.any() else 0}",
        "*",
    ]
    um = rows_bottom_up(h * 1e6) if ny > 1 else h.T * 1e6
    bad = rows_bottom_up(mask) if ny > 1 else mask.T
    for row, brow in zip(um, bad):
        lines.append(" ".join("BAD" if b else f"{v:.5f}" for v, b in zip(row, brow)))
    lines += ["*", ""]
    path.write_text("\n".join(lines), encoding="ascii")


# ----------------------------------------------------------------------------- Digital Surf
def write_sur(path: Path, h: np.ndarray, mask: np.ndarray) -> None:
    """Digital Surf .sur (MountainsMap): 512-byte little-endian header, int32 points line
    after line (x fastest); height = (raw − Zmin)·dz + Z offset in the z unit;
    non-measured points = Zmin − 2 with the special-points flag set."""
    nx, ny = h.shape
    dz_um = 1e-4  # 0.1 nm per count
    um = h * 1e6
    z0 = float(np.floor(um.min()))
    raw = np.round((um - z0) / dz_um).astype(np.int64)
    zmin, zmax = int(raw.min()), int(raw.max())
    raw = np.where(mask, zmin - 2, raw).astype("<i4")
    data = (rows_bottom_up(raw) if ny > 1 else raw.T).tobytes()
    unit = "µm".encode("latin-1")
    hd = bytearray(512)

    def put(off, fmt, *vals):
        struct.pack_into("<" + fmt, hd, off, *vals)

    hd[0:12] = b"DIGITAL SURF"
    put(12, "h", 0)  # format: PC
    put(14, "h", 1)  # number of objects
    put(16, "h", 1)  # version
    put(18, "h", 2 if ny > 1 else 1)  # object type: 2 surface, 1 profile
    hd[20:50] = b"tribodyn test surface".ljust(30)
    hd[50:80] = b"synthetic".ljust(30)
    put(80, "h", 0)  # material code
    put(82, "h", 2)  # acquisition: optical
    put(84, "h", 0)  # range type
    put(86, "h", 1 if mask.any() else 0)  # special (non-measured) points
    put(88, "h", 1)  # absolute heights
    put(90, "f", 0.0)  # gauge resolution
    put(94, "i", 0)  # W size
    put(98, "h", 32)  # bits per point
    put(100, "i", zmin)
    put(104, "i", zmax)
    put(108, "i", nx)  # points per line
    put(112, "i", ny)  # number of lines
    put(116, "i", nx * ny)
    put(120, "f", (DX if ny > 1 else DXP) * 1e6)  # x spacing [µm]
    put(124, "f", DX * 1e6 if ny > 1 else 1.0)  # y spacing [µm]
    put(128, "f", dz_um)  # z spacing [µm]
    for off, text in ((132, b"X"), (148, b"Y"), (164, b"Z")):
        hd[off : off + 16] = text.ljust(16, b"\0")
    for off in (180, 196, 212, 228, 244, 260):  # step and length units
        hd[off : off + 16] = unit.ljust(16, b"\0")
    put(276, "fff", 1.0, 1.0, 1.0)  # unit ratios
    put(288, "hhh", 0, 0, 0)  # imprint, inverted, levelled
    put(306, "hhhhhhh", 12, 11, 10, 6, 5, 2024, 1)  # time and date
    put(320, "f", 1.0)  # measurement duration
    put(334, "hh", 0, 0)  # comment and private sizes
    put(466, "fff", 0.0, 0.0, z0)  # x, y, z offsets (z in µm)
    path.write_bytes(bytes(hd) + data)


# ----------------------------------------------------------------------------- Zygo MetroPro
def write_metropro(path: Path, h: np.ndarray, mask: np.ndarray) -> None:
    """Zygo MetroPro .dat, header format 1 (834 bytes, big-endian; MetroPro Reference
    Guide, "Data file format"): no intensity data, phase as int32 rows of cn_width
    values, row 0 at the top; height = phase · S·O·λ/R with R = 4096 (phase_res 0);
    invalid phase ≥ 2147483640."""
    nx, ny = h.shape
    wavelength, scale, obliquity = 632.8e-9, 0.5, 1.0
    q = scale * obliquity * wavelength / 4096.0  # m per count
    phase = np.round(h / q).astype(np.int64)
    phase = np.where(mask, 2147483647, phase).astype(">i4")
    data = rows_top_down(phase).tobytes()
    hd = bytearray(834)

    def put(off, fmt, *vals):
        struct.pack_into(">" + fmt, hd, off, *vals)

    put(0, "I", 0x881B036F)  # magic number, format 1
    put(4, "h", 1)  # header format
    put(6, "i", 834)  # header size
    put(10, "h", 1)  # software type: MetroPro
    hd[12:42] = b"Mon May  6 10:11:12 2024".ljust(30, b"\0")
    put(42, "hhh", 8, 3, 0)  # version 8.3.0
    put(48, "hhhhhh", 0, 0, 0, 0, 0, 0)  # no intensity data
    put(60, "i", 0)
    put(64, "hhhh", 0, 0, nx, ny)  # phase origin and size
    put(72, "i", 4 * nx * ny)  # phase bytes
    put(76, "i", 1714990272)  # time stamp
    hd[80:162] = b"tribodyn test surface".ljust(82, b"\0")
    put(162, "h", 1)  # source: measured
    put(164, "f", scale)  # interferometric scale factor
    put(168, "f", wavelength)  # wavelength in
    put(172, "f", 0.3)  # numerical aperture
    put(176, "f", obliquity)  # obliquity factor
    put(180, "f", 50.0)  # magnification
    put(184, "f", DX)  # lateral resolution [m]
    put(218, "h", 0)  # phase resolution: normal
    path.write_bytes(bytes(hd) + data)


# ----------------------------------------------------------------------------- Wyko OPD
def write_opd(path: Path, h: np.ndarray, mask: np.ndarray) -> None:
    """Wyko/Veeco Vision .opd: 2 bytes, a directory of 24-byte blocks (name[16], type u16,
    size u32, flags u16; little-endian), the blocks' data in order. The "OPD" array
    (type 3) holds nx, ny, element size 4, then float32 in units of the wavelength
    column by column (x), each from the bottom (y = 0) up; bad points ≥ 1e38.
    "Wavelength" [nm], "Pixel_size" [mm], "Mult" and "Aspect" are floats (type 7)."""
    nx, ny = h.shape
    wavelength_nm, mult = 632.8, 1.0
    waves = (h * 1e9 / wavelength_nm * mult).astype("<f4")
    waves = np.where(mask, np.float32(1e38 * 1.5), waves).astype("<f4")
    array = struct.pack("<HHH", nx, ny, 4) + waves.tobytes()  # [ix][iy], iy fastest
    blocks = [
        ("OPD", 3, array),
        ("Wavelength", 7, struct.pack("<f", wavelength_nm)),
        ("Pixel_size", 7, struct.pack("<f", DX * 1e3)),
        ("Mult", 7, struct.pack("<f", mult)),
        ("Aspect", 7, struct.pack("<f", 1.0)),
        ("Title", 5, b"tribodyn test surface"),
    ]
    n = len(blocks) + 1
    head = bytearray(b"\x01\x00")

    def entry(name, typ, size, flags):
        return name.encode().ljust(16, b"\0") + struct.pack("<HIH", typ, size, flags)

    head += entry("Directory", 1, 24 * n, 0xFFFF)
    for name, typ, payload in blocks:
        head += entry(name, typ, len(payload), 0)
    path.write_bytes(bytes(head) + b"".join(p for _, _, p in blocks))


# ----------------------------------------------------------------------------- Sensofar PLU
def write_plu(path: Path, h: np.ndarray, mask: np.ndarray) -> None:
    """Sensofar PLU (format version 2006): 500-byte little-endian header (date string,
    time, comment, axis calibration with µm per pixel, measurement configuration, type 3 =
    topography, one layer, no images), then rows u32, columns u32, float32 heights in µm
    row after row from the top, and the data minimum and maximum (float32); non-measured
    points = 1000001."""
    nx, ny = h.shape
    um = np.where(mask, np.float32(1000001.0), (h * 1e6).astype("<f4")).astype("<f4")
    hd = bytearray(500)

    def put(off, fmt, *vals):
        struct.pack_into("<" + fmt, hd, off, *vals)

    hd[0:128] = b"Mon May 06 10:11:12 2024".ljust(128, b"\0")
    put(128, "I", 1714990272)
    hd[132:388] = b"tribodyn test surface".ljust(256, b"\0")
    put(388, "III", ny, nx, nx * ny)  # calibration: rows, columns, N
    put(400, "fffffff", 1.0, DX * 1e6, DX * 1e6, 0.0, 0.0, 1.0, 0.0)
    put(428, "IIIIIIIIII", 3, 0, 0, 5, 3, nx, ny, nx, ny, 0)  # topography, confocal
    put(468, "d", 0.1)  # z increment
    put(476, "f", 10.0)  # range
    put(480, "II", 100, 0)  # planes, threshold
    hd[488:494] = bytes([0, 1, 0xFF, 0, 0, 0])  # restore, layers, version 2006, …
    put(496, "I", 1)
    valid = (h * 1e6)[~mask]
    data = (
        struct.pack("<II", ny, nx)
        + rows_top_down(um).tobytes()
        + struct.pack("<ff", valid.min(), valid.max())
    )
    path.write_bytes(bytes(hd) + data)


FILES = {
    "surface.x3p": write_x3p,
    "surface.sdf": write_sdf,
    "surface.sur": write_sur,
    "surface.dat": write_metropro,
    "surface.opd": write_opd,
    "surface.plu": write_plu,
}
PROFILES = {"profile.sdf": write_sdf, "profile.sur": write_sur}


def main() -> None:
    h, m = surface(), dropouts()
    for name, write in FILES.items():
        write(HERE / name, h, m)
    p, pm = profile()[:, None], profile_dropouts()[:, None]
    for name, write in PROFILES.items():
        write(HERE / name, p, pm)


if __name__ == "__main__":
    main()
