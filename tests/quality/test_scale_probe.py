"""The stage probe of docs/scaling.md ("One machine"): sizes, statuses and memory readings of a
small dome, checked against the dome's closed-form counts."""

import pytest

from tce.quality.scale import dome_stages, memory
from tce.structures import params


def test_memory_reads_this_process():
    rss, peak = memory()
    assert 0 < rss <= peak


def test_dome_stages_small_dome():
    n = 6
    r = dome_stages(n)
    # closed forms: n supports + n * n voussoirs; a free block has 6 equilibrium rows and each
    # contact vertex 3 unknowns and one 3D cone (3 rows)
    assert r["n_blocks"] == n * (n + 1)
    assert r["n_vars"] == 3 * r["n_contacts"]
    assert r["rows"] == 6 * n * n + 3 * r["n_contacts"]
    assert r["status"] == "Solved" and r["iterations"] > 0 and r["lambda_max"] > 0
    names = [s["stage"] for s in r["stages"]]
    assert names[0] == "imports" and names[-1] == "Clarabel solved" and len(names) == 7
    peaks = [s["peak_gb"] for s in r["stages"]]
    assert peaks == sorted(peaks)  # the peak so far never falls
    assert all(s["rss_gb"] <= s["peak_gb"] for s in r["stages"])


def test_dome_stages_raises_the_block_limit_only_when_asked(monkeypatch):
    monkeypatch.setattr(params, "MAX_BLOCKS", 20)
    with pytest.raises(ValueError, match="MAX_BLOCKS"):
        dome_stages(6)
    assert dome_stages(6, max_blocks=42)["n_blocks"] == 42
