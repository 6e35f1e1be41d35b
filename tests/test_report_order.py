"""The run report opens with what an engineer asks first — coating verdict, camshaft
torque and contact pressure, films and λ — and shows the paper's method comparisons
(explicit vs implicit dynamics, coating moduli) after the engineering figures; its
HTML holds the interactive traces."""

import re

from tribodyn.output.report_first import figure_rank, verdict_section


def test_report_sections_engineer_first(reduced_results):
    md = (reduced_results / "report.md").read_text(encoding="utf-8")
    heads = re.findall(r"^##+ (.+)$", md, flags=re.M)
    assert heads[:3] == [
        "Coating verdict",
        "Camshaft torque and contact pressure",
        "Films, λ and friction per tappet surface",
    ]
    assert heads.index("Figures") < heads.index("Method") < heads.index("Numerics")
    figs = re.findall(r"^!\[[^\]]*\]\((\S+)\)", md, flags=re.M)
    assert figs[0] == "fig23_camshaft_torque.png"
    methods = md.index("### Method comparisons")
    assert md.index("](fig08_tappet_velocity.png)") > methods
    assert md.index("](fig20_min_film_lambda.png)") < methods
    page = (reduced_results / "report.html").read_text(encoding="utf-8")
    assert page.index("<h2>Interactive traces</h2>") < page.index("<h2>Figures</h2>")


def test_verdict_says_lower_or_not_with_the_change():
    summ = {
        "reference_set": "a",
        "surface_sets": {
            "a": {"label": "steel", "friction_energy_per_cycle_J": 2.0, "min_film_m": 1e-7},
            "b": {"label": "DLC 1 µm", "friction_energy_per_cycle_J": 1.5, "min_film_m": 1.1e-7},
            "c": {"label": "WC-C 1 µm", "friction_energy_per_cycle_J": 2.5},
            "d": {
                "label": "X",
                "friction_energy_per_cycle_J": 1.0,
                "coating_verdict": {
                    "sentence": "X lowers friction energy per cycle by 50 % (given)",
                    "range_independent_pct": [-60.0, -40.0],
                    "method": "as the summary says",
                },
            },
        },
    }
    text = "\n".join(verdict_section(summ))
    assert "**DLC 1 µm** lowers the friction: friction energy per cycle −25.0 %" in text
    assert "minimum film h_min +10.0 %" in text
    assert "**WC-C 1 µm** does not lower the friction: friction energy per cycle +25.0 %" in text
    # a coating_verdict of the summary is quoted, with its method and independent range
    assert "**X lowers friction energy per cycle by 50 % (given)** (1 J vs 2 J)" in text
    assert "How the range was computed: as the summary says" in text
    assert "With each pair's ς varied on its own: X −60 … −40 %." in text
    assert figure_rank("fig23") < figure_rank("fig99") < figure_rank("fig08")
