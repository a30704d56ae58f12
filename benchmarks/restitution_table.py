"""The effective coefficient of restitution of every damping law against its nominal e, at
impact speeds 1e-5 to 1 m/s (1e-5 below the damping guard v_min = 1e-4 m/s), by
`sim restitution` (sim.model.restitution): the table of docs/model.md, "Contact laws", printed
as Markdown.

Usage:
    python benchmarks/restitution_table.py
"""

from sim.model.contact_laws import LAW_NAMES
from sim.model.restitution import effective_restitution

NOMINALS = (0.1, 0.3, 0.5, 0.7, 0.9)
SPEEDS = (1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0)


def main() -> None:
    header = "| law | e | " + " | ".join(f"{v:g} m/s" for v in SPEEDS) + " |"
    print(header)
    print("|" + "---|" * (len(SPEEDS) + 2))
    for law in LAW_NAMES:
        for e in NOMINALS:
            cells = " | ".join(f"{effective_restitution(law, e, v):.3f}" for v in SPEEDS)
            print(f"| {law} | {e:g} | {cells} |")


if __name__ == "__main__":
    main()
