"""A figure from a sweep's table: one metric against one varied key.

Mean and 95 % confidence interval (Student's t over the repetitions) per
value of ``x``, one line per value of ``by``; failed runs are left out and
counted in the legend's title.
"""

from __future__ import annotations

from pathlib import Path

from .spec import SweepError
from .store import atomic_write


def plot_metric(table: Path, x: str, y: str, by: str | None, out: Path, title: str = "",
                sim: Path | None = None) -> None:
    """The figure; with `sim`, the x axis and the legend name the keys by
    their documented meaning and unit (swarmtools.keydocs)."""
    import io

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd
    from scipy import stats

    from swarmtools.keydocs import label as key_label
    from swarmtools.keydocs import meaning

    try:
        df = pd.read_parquet(table)
    except (OSError, ValueError) as e:
        raise SweepError(f"{table}: cannot read the table: {e}") from None
    for col, what in ((x, "--x"), (y, "--y"), (by, "--by")):
        if col is not None and col not in df.columns:
            raise SweepError(f"{what} {col}: not a column of {table} (columns: {', '.join(df.columns)})")
    failed = int((df["status"] != "ok").sum())
    df = df[df["status"] == "ok"]
    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    groups = [(None, df)] if by is None else list(df.groupby(by, sort=True))
    for key, g in groups:
        s = g.groupby(x, sort=True)[y].agg(["mean", "std", "count"])
        half = s["std"] / s["count"] ** 0.5 * stats.t.ppf(0.975, (s["count"] - 1).clip(lower=1))
        label = None if by is None else f"{(meaning(by, sim) if sim else None) or by} = {key}"
        ax.errorbar(s.index, s["mean"], yerr=half.fillna(0), marker="o", capsize=3, label=label)
    ax.set_xlabel(key_label(x, sim) if sim else x)
    ax.set_ylabel(f"{y} (mean, 95 % CI)")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    if by is not None or failed:
        ax.legend(title=f"{failed} failed runs left out" if failed else None)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    plt.close(fig)
    atomic_write(out, buf.getvalue())
