"""Values transcribed from the thesis (Restrepo, EAFIT 2010), exactly as printed.

This module is the *only* place where published numbers live. They are used solely as
"the published value to compare against"; nothing computed in this project is taken from here.

The tables are kept as the printed text (decimal commas, printed signs and rounding) and parsed
on import, so a reader can check each line against the thesis. Units are recorded **as printed in
the column headers**; whether the numbers really are in those units is a question the book
answers (see ``notebooks/published_doe.ipynb``), not one this module decides.

Sources (section numbers of ``shared/paper/thesis.md``):

- Table 1 (sec. 2.6.1): factor levels.
- Table 2 (sec. 2.6.2): 12-run Plackett–Burman design and responses.
- Table 3 (sec. 2.6.2): Lenth's analysis; the list after it (items 1–4): the main factors.
- Table 4 (sec. 2.6.3): 30-run uniform design and responses.
- Eq 8 (sec. 2.6.4): the fitted input–output matrix S_T.
- Table 5 (sec. 2.6.5): validation errors of the meta-model over 1000 random runs.
- Table 7 (sec. 3.7): nominal and disturbed ("real") 5R parameters.
- Table 8 (sec. 3.7): regressor sizes and costs as printed.

One block is not from the thesis: the CD² of the published uniform design of Table 4's size,
U30(6^6), to compare Table 4 with (see ``UD_U30_6_6_CD2``).
"""

from __future__ import annotations

import numpy as np

FACTORS: tuple[str, ...] = ("T1D1", "T1D2", "T2D1", "T2D2", "T3D1", "T3D2")
"""Factor (actuator) names in the order of Eq 4."""

RESPONSES: tuple[str, ...] = ("x", "y", "z", "θx", "θy", "θz")
"""Pose components (the responses) in the order of Eq 5: the one spelling of their labels."""

RESPONSE_UNITS: tuple[str, ...] = ("µm", "µm", "µm", "µrad", "µrad", "µrad")
"""Units of the pose components: Eq 5's, and the column headers of Tables 2 and 4 (but see
:func:`table2_responses_um_urad`)."""


def printed_resolution(text: str) -> np.ndarray:
    """Half a unit of the last printed digit of every cell of a printed block.

    ``"0,17"`` gives 0.005, ``"575314"`` gives 0.5 and ``"4,01E-04"`` gives 5e-7: the largest
    difference that printing alone can explain.
    """
    rows = [line.split() for line in text.strip().splitlines() if line.strip()]
    out = []
    for row in rows:
        res = []
        for cell in row:
            mant, _, exp = cell.upper().partition("E")
            dec = mant.replace(".", ",").partition(",")[2]
            res.append(0.5 * 10.0 ** (-len(dec)) * 10.0 ** (int(exp) if exp else 0))
        out.append(res)
    return np.array(out)


def parse_printed(text: str) -> np.ndarray:
    """Parse a whitespace-separated block of numbers printed with decimal commas.

    Parameters
    ----------
    text : str
        Rows separated by newlines, cells by blanks; ``"0,6"`` means 0.6 and
        ``"4,01E-04"`` means 4.01e-4.

    Returns
    -------
    numpy.ndarray
        2-D float array, one row per printed row.

    Raises
    ------
    ValueError
        If the rows do not all have the same number of cells or a cell is not a number.
    """
    rows = [line.split() for line in text.strip().splitlines() if line.strip()]
    widths = {len(r) for r in rows}
    if len(widths) != 1:
        raise ValueError(f"printed table rows must have equal length, got lengths {sorted(widths)}")
    try:
        return np.array([[float(c.replace(",", ".")) for c in r] for r in rows])
    except ValueError as err:
        raise ValueError(f"printed table holds a cell that is not a number: {err}") from None


# --- Table 1: studied factors, forces in the tabs [N] --------------------------------------
TABLE1_LOW_N: float = -1.0
TABLE1_HIGH_N: float = 1.0

# --- Table 2: Plackett–Burman design (6 factors, 12 runs) and responses -----------------------
# columns: T1D1 T1D2 T2D1 T2D2 T3D1 T3D2 [N] | x y z [µm as printed] | θx θy θz [µrad as printed]
_TABLE2 = """
            1        -1         1        -1        -1        -1    115056       0,6   -862976    0,0001   -0,0001   3,10176
           -1        -1         1         1         1        -1    -57529   99636,5   -287659  -39,3596  -68,0656   3,10183
            1        -1        -1        -1         1         1        -3      -0,6   -287655  -39,2665   68,1194  -9,30545
           -1        -1        -1        -1        -1        -1    -57525  -99636,5   -862976    0,0001   -0,0001   3,10186
            1         1        -1         1         1        -1        -3      -0,6    287655   39,2665  -68,1194  -9,30545
            1         1         1        -1         1         1     57525   99636,5    287659   39,3596   68,0656  -3,10186
           -1        -1        -1         1         1         1   -115056      -0,6    287662  -78,6262    0,0539  -3,10176
           -1         1        -1        -1        -1         1    -57525  -99636,5    287659   39,3596   68,0656   3,10186
           -1         1         1         1        -1         1         3       0,6    862976   -0,0001    0,0001   9,30545
           -1         1         1        -1         1        -1    -57529   99636,5   -287662   78,6262   -0,0539   3,10183
            1         1        -1         1        -1        -1     57529  -99636,5    287655   39,2665  -68,1194  -3,10183
            1        -1         1         1        -1         1    115056       0,6    287662  -78,6262    0,0539   3,10176
"""
TABLE2 = parse_printed(_TABLE2)
TABLE2_DESIGN = TABLE2[:, :6]
TABLE2_RESPONSES = TABLE2[:, 6:]
TABLE2_RESPONSES_RESOLUTION = printed_resolution(_TABLE2)[:, 6:]
#: Table 2's printed numbers per unit of its header: it is printed in nm and mrad, not the µm and
#: µrad its header says (Eq 8 applied to its forces gives translations ≈ 1000 times smaller and
#: rotations ≈ 1000 times larger; the published-data page measures these ratios).
TABLE2_PRINTED_PER_HEADER_UNIT = np.array([1e3, 1e3, 1e3, 1e-3, 1e-3, 1e-3])
#: the units Table 2's numbers (and so Table 3's) are in, per pose component
TABLE2_PRINTED_UNITS: tuple[str, ...] = ("nm", "nm", "nm", "mrad", "mrad", "mrad")


def table2_responses_um_urad() -> np.ndarray:
    """Table 2's responses (12, 6) converted to the µm and µrad of its header, of Table 4 and of
    Eq 8: the printed values divided by :data:`TABLE2_PRINTED_PER_HEADER_UNIT`."""
    return TABLE2_RESPONSES / TABLE2_PRINTED_PER_HEADER_UNIT


# --- Table 3: Lenth's analysis, as printed -------------------------------------------------
# rows are listed in the printed order; columns x y z [µm] θx θy θz [µrad] (printed units).
TABLE3_EFFECT_ROWS: tuple[str, ...] = ("T1D2", "T2D2", "T3D2", "T2D1", "T3D1", "T1D1")
_TABLE3_EFFECTS = """
    0,17         0    575314     78,63      0,05       0
    0,17         0    575317     39,36     68,07       0
    0,17         0    575321     39,27     68,12       0
 57527,5   99637,1         0         0         0     6,2
 57531,5   99635,9         0         0         0     6,2
115053,5         0         0         0         0     6,2
"""
TABLE3_EFFECTS = parse_printed(_TABLE3_EFFECTS)
TABLE3_EFFECTS_RESOLUTION = printed_resolution(_TABLE3_EFFECTS)
_TABLE3_SUMMARY = """
   19,63         0    287657     19,63      0,03     3,1
   29,45         0  431485,5     29,45      0,04    4,65
  110,73         0         0         0         0       0
  265,34         0         0         0         0       0
"""
TABLE3_SUMMARY_ROWS: tuple[str, ...] = ("ν", "S₀", "ME", "SME")
TABLE3_SUMMARY = parse_printed(_TABLE3_SUMMARY)
TABLE3_SUMMARY_RESOLUTION = printed_resolution(_TABLE3_SUMMARY)

# --- sec. 2.6.2, the list after Table 3: the factors that "mainly affect" each response -------
# items 1–4, one set per response in the order of Eq 5 (x, y, z, θx, θy, θz).
SEC262_MAIN_FACTORS: tuple[frozenset[str], ...] = (
    frozenset({"T1D1", "T2D1", "T3D1"}),  # item 1: x
    frozenset({"T2D1", "T3D1"}),  # item 3: y
    frozenset({"T1D2", "T2D2", "T3D2"}),  # item 2: z
    frozenset({"T1D2", "T2D2", "T3D2"}),  # item 2: θx
    frozenset({"T2D2", "T3D2"}),  # item 4: θy
    frozenset({"T1D1", "T2D1", "T3D1"}),  # item 1: θz
)

# --- Table 4: uniform design (6 factors, 30 runs) and responses -----------------------------
# columns as Table 2.
_TABLE4 = """
          0,6      -0,2        -1        -1         1      -0,2       -23         0   -403,37  15723,33   27294,4  -8057,19
         -0,6      -0,6       0,2         1        -1       0,2         0    -39,85    172,88 -47310,09 -27294,38   5583,32
         -0,2       0,2      -0,2        -1        -1       0,6      11,5    -59,78    -57,63  15769,99  54588,86   3098,05
           -1      -0,2         1       0,6      -0,2         1    -23,01     39,85    403,37 -39390,09  13647,29   6831,66
            1       0,2         1         1       0,6       0,2     69,02     79,71    403,37 -15723,33  -27294,4  -1883,93
           -1        -1      -0,2        -1      -0,2        -1    -57,52    -19,93   -864,35   -116,71     -0,06   3120,86
         -0,6       0,2        -1         1       0,2       0,6    -69,02    -39,85    518,61 -23596,69 -13647,16  -1838,28
          0,6      -0,6       0,6       0,6       0,2        -1     46,01     39,85   -288,11 -15816,67 -54588,89   -635,59
           -1         1      -0,6      -0,2      -0,6       0,2    -57,52    -59,78     288,1  39483,43   13647,2   3120,87
          0,2         1       0,2         1      -0,2      -0,6     23,01         0    403,35  31610,14 -54588,88    612,76
         -0,6       0,6       0,2        -1       0,2         1    -34,51     19,93    172,86  23690,01  68236,09   1872,51
            1        -1      -0,2       0,6      -0,6      -0,2     69,02    -39,85   -172,86 -47356,77 -27294,41  -1883,92
           -1       0,6      -0,2       0,6       0,6      -0,2    -80,53     19,93    288,11  15816,74 -27294,44    646,99
           -1       0,2       0,6      -0,6         1      -0,6    -69,02     79,71   -288,12  31516,73     -0,05   1883,92
            1         1       0,6        -1      -0,2       0,2     80,52     19,93     57,61   55230,1  40941,61   -646,99
            1       0,6        -1       0,2       0,2      -0,6     23,01    -39,85     57,61  31563,44 -27294,47  -6831,66
          0,2         1      -0,6      -0,6       0,6        -1    -23,01         0   -172,89  70976,84  -13647,3  -4334,97
          0,6       0,6      -0,6       0,6        -1         1     46,02    -79,71    633,86  -7803,34  13647,27   -635,57
          0,2       0,2       0,6       0,2      -0,6      -0,2     46,01         0     57,62    7896,7 -13647,22   3086,63
          0,6      -0,2       0,2      -0,6        -1      -0,6     69,02    -39,85   -403,37  15723,35     -0,04   1838,29
          0,6      -0,6         1      -0,6      -0,6       0,6     80,52     19,93   -172,86  -23690,1  40941,67   3075,22
          0,2        -1       0,2       0,2         1         1     -11,5     59,78     57,64 -63103,51  27294,51  -3098,05
         -0,2       0,6         1      -0,2        -1        -1     46,01         0   -172,88  47310,13  -27294,5   6808,84
         -0,6        -1         1      -0,2       0,6      -0,2    -23,01     79,71   -403,35  -31610,1         0   3109,44
         -0,2      -0,6      -0,6      -0,6       0,2       0,2    -34,51    -19,93   -288,11 -15816,74  27294,44  -1849,69
         -0,2      -0,6      -0,6         1         1      -0,6    -57,52     19,93    -57,62 -31563,37 -54588,85  -4323,57
         -0,6      -0,2        -1       0,2      -0,6        -1    -46,01    -79,71   -288,12   7850,04 -40941,69    635,59
         -0,2         1       0,6       0,2         1       0,6    -23,01     79,71     518,6  23736,74  13647,23   -612,77
            1      -0,2      -0,2      -0,2       0,6         1     34,51     19,93    172,88 -23643,42   40941,7  -5594,73
          0,2        -1        -1      -0,2      -0,2       0,6     -11,5    -59,78   -172,85 -47356,81  27294,48  -3098,03
"""
TABLE4 = parse_printed(_TABLE4)
TABLE4_DESIGN = TABLE4[:, :6]
TABLE4_RESPONSES = TABLE4[:, 6:]
TABLE4_RESPONSES_RESOLUTION = printed_resolution(_TABLE4)[:, 6:]

# --- Not from the thesis: CD² of the published U30(6^6) uniform designs ---------------------
# Source: the UniDOE package's repository (Zhang, Li and Quan; GitHub HAOYU-LI/UniDOE, commit
# 4f59a40b5f7f287c79e46cdb83a6b5b2d535da60), file
# "Advanced_Designs/CL2_nsq/Discrepancy/Dis_ CL2_30_6_6.csv" (the blank is in the file name):
# "prev_dis" is the CD² that UniDOE's Eval(crit = "CL2") gives for the 30-run, 6-factor,
# 6-level table of the Uniform Design website (www.cms-ud.com/UD/UniformDesign.html), which
# that repository's Advanced_Designs/README.md and src/new_design_CLnsq.R say it re-evaluated;
# "new_dis" is the CD² of UniDOE's re-optimised design of the same size. Both are squared CD
# with levels at (k - 1/2)/q, printed to 16 decimals. (The website's table itself, stored there
# as Advanced_Designs/CL2_nsq/CL2_30_6_6.csv, has the rows of Table 4 in the same order, level k
# being the force -1 + 0.4 (k - 1) N; checked once by hand, not used here.)
_UD_U30_6_6_CD2 = "0.0279400614207479 0.0277121676372092"
UD_U30_6_6_CD2: float = float(parse_printed(_UD_U30_6_6_CD2)[0, 0])
"""CD² of the Uniform Design website's U30(6^6) table (UniDOE's "prev_dis")."""
UNIDOE_U30_6_6_CD2: float = float(parse_printed(_UD_U30_6_6_CD2)[0, 1])
"""CD² of UniDOE's re-optimised U30(6^6) design ("new_dis")."""
UD_U30_6_6_CD2_RESOLUTION: float = float(printed_resolution(_UD_U30_6_6_CD2)[0, 0])

# --- Eq 8: S_T, "rows 1 to 3 µm/N and rows 3 to 6 µrad/N" (sic) -----------------------------
_EQ8 = """
  57.53       0     28.76          0    -28.76        0
      0       0     49.82          0     49.82        0
      0  287.66         0     287.66         0   287.66
      0 39313.03        0  -19679.85         0 -19633.3
      0       0         0  -34032.01         0 34060.19
-3101.84      0   3101.79          0  -3101.81        0
"""
EQ8_ST = parse_printed(_EQ8)
EQ8_ST_RESOLUTION = printed_resolution(_EQ8)

# --- Table 5: meta-model vs ANSYS, 1000 random runs ---------------------------------------
# rows x y z [µm] θx θy θz [µrad]; columns MAXABS, MAX %error, RMSE.
TABLE5_COLUMNS: tuple[str, ...] = ("MAXABS", "MAX_pct_error", "RMSE")
_TABLE5 = """
4,01E-04 1,08E-03 8,67E-05
4,18E-04 3,59E-04 2,07E-05
2,85E-04 2,41E-04 4,19E-05
2,41E-02 2,26E-03 9,78E-04
4,16E+00 6,21E-01 5,57E-03
2,10E-02 2,30E-03 2,23E-03
"""
TABLE5 = parse_printed(_TABLE5)
TABLE5_RESOLUTION = printed_resolution(_TABLE5)
TABLE5_N_RUNS: int = 1000

# --- sec. 2.7 (conclusions): the yardsticks by which the thesis judges Table 5 ----------------
TABLE5_ACCEPTABLE_MAXABS_UM: float = 19.0
"""The ISO h6 tolerance of a Ø50 mm shaft (50 −19/+0 µm) against which sec. 2.7 finds Table 5's
largest absolute error acceptable [µm]."""
TABLE5_PETRI_REL_ERROR_PCT: float = 3.0
"""The largest relative error of P. A. Petri's beam model against FEA (thesis ref. [55]), which
sec. 2.7 says Table 5's relative errors improve on [%]."""

# --- Table 7: planar 5R parameters, nominal and disturbed ("real") --------------------------
# printed order; lengths in m, angles in rad, gains dimensionless.
TABLE7_NAMES: tuple[str, ...] = (
    "A1x",
    "A1y",
    "k1",
    "gamma1",
    "l1",
    "L1",
    "A2x",
    "A2y",
    "l2",
    "L2",
    "k2",
    "gamma2",
)
_TABLE7 = """
-0.5000 -0.4988
 0.0000  0.0028
 1.0000  1.004
 0.0000  0.0048
 0.7500  0.7507
 1.1000  1.0995
 0.5000  0.4961
 0.0000  0.0066
 0.7500  0.7559
 1.1000  1.0959
-1.0000 -0.9984
 3.1416  3.1418
"""
TABLE7 = parse_printed(_TABLE7)
#: Table 7's unit column ("" where the thesis prints none: the joint gains k are unitless)
TABLE7_UNITS: dict[str, str] = {
    "A1x": "m", "A1y": "m", "k1": "", "gamma1": "rad", "l1": "m", "L1": "m",
    "A2x": "m", "A2y": "m", "l2": "m", "L2": "m", "k2": "", "gamma2": "rad",
}  # fmt: skip
TABLE7_NOMINAL = dict(zip(TABLE7_NAMES, TABLE7[:, 0], strict=True))
TABLE7_REAL = dict(zip(TABLE7_NAMES, TABLE7[:, 1], strict=True))

# --- Section 3.7, items 8–10 and Table 8 ----------------------------------------------------
SEC37_POSTURES_PER_LEG: int = 18
SEC37_POSTURES_TRADITIONAL: int = 36
SEC37_NOISE_SIGMA: float = 1e-4
TABLE8_REGRESSOR_TRADITIONAL: tuple[int, int] = (36, 36)
TABLE8_REGRESSOR_DC: tuple[int, int] = (18, 18)
TABLE8_MEASUREMENTS_TRADITIONAL: int = 72  # printed as 2·18·2
TABLE8_MEASUREMENTS_DC: int = 108  # printed as 18·2(2+1)

# --- Tables 6 and 8 as printed (symbols and products, not computed values) ------------------
#: Table 6 (sec. 3.6), rows then columns (traditional, divide and conquer), as printed.
TABLE6_ROWS: tuple[str, ...] = ("Regressor", "Computational cost (matrix inversion)")
TABLE6_PRINTED: dict[str, tuple[str, ...]] = {
    "traditional": ("CᵀC (N n_limbs × N n_limbs)", "∝ N³ n_limbs³"),
    "divide and conquer": ("C_κᵀC_κ (N × N)", "∝ N³ n_limbs"),
}
#: Table 8 (sec. 3.7), rows then columns, as printed.
TABLE8_ROWS: tuple[str, ...] = (*TABLE6_ROWS, "Measurement cost")
TABLE8_PRINTED: dict[str, tuple[str, ...]] = {
    "traditional": ("CᵀC (36 × 36)", "∝ 18³ · 2³", "2 · 18 · 2 = 72"),
    "divide and conquer": ("C_κᵀC_κ (18 × 18)", "∝ 18³ · 2", "18 · 2(2 + 1) = 108"),
}
