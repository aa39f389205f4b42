"""srb-rolling's finite-body reference sends its FE correction levels to a dask cluster (``femcheck run
--scheduler``): on a LocalCluster the tables come back equal to the ones solved in this process, land in the result
cache where the reference reads them, and a level already cached is not sent again."""
from __future__ import annotations

import numpy as np
import pytest

from femcheck import executor
from femcheck.fem import compliance_store
from femcheck.problems import _srb_rolling_fb as fb
from femcheck.scene import load_scene

# a small, coarse correction family: level 1 is 11 x 11 cells over the roller
CHEAP = {"numerics.fb_correction_cells_x": 5, "numerics.fb_correction_cells_s": 7, "numerics.fb_h_contact": 1.4,
         "numerics.fem_grading": 1.0}


def test_run_scheduler_is_set_only_within_the_run():
    assert executor.current_scheduler() is None
    with executor.remote("tcp://somewhere:8786"):
        assert executor.current_scheduler() == "tcp://somewhere:8786"
    assert executor.current_scheduler() is None


@pytest.mark.slow
def test_correction_levels_solved_on_a_local_cluster_equal_local_ones(tmp_path, monkeypatch):
    distributed = pytest.importorskip("distributed")
    monkeypatch.setenv("FEMCHECK_CACHE", str(tmp_path))
    p = load_scene("srb-rolling-finite", CHEAP).params
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) \
            as cluster:
        # the coarsest level is always solved here (a stored reference records its meshes): not sent
        assert fb.prefetch(p, [(0, None), (1, None)], cluster.scheduler_address) == [(1, None)]
        assert fb._tables_path(p, 1, None).is_file()
        assert fb.prefetch(p, [(0, None), (1, None)], cluster.scheduler_address) == []     # cached: nothing sent
    remote = compliance_store.load(fb._tables_path(p, 1, None), fb.correction_grid(p, 1)[3])
    local = fb._tables_case((p, 1, None))
    assert set(remote.tables) == set(local.tables) == {(a, b) for a in ("inner", "outer") for b in ("inner", "outer")}
    for key, T in local.tables.items():
        scale = np.abs(T).max()
        assert scale > 0
        np.testing.assert_allclose(remote.tables[key], T, rtol=0, atol=1e-9 * scale)
        assert remote.lag0[key] == local.lag0[key]
