"""Priors learned across tasks on a Dask cluster: `rccpack priors` with the
per-task step run on the workers.

Each task folder (`demos.json` and `learned.rcc`) is counted on a worker
with `rccpack.task_counts` (plain, JSON-able data: a hash and, per kind of
statement, the candidates and the kept and confirmed rules); the counts are
gathered on the client and `rccpack.combine_priors` turns them into the
priors file: the same bytes as `rccpack priors FOLDER... -o priors.json`
with the same parameters, in any folder order and on any number of workers.
The workers must see the folders at the same paths (a shared file system).

    from dask.distributed import Client
    from dask_priors import priors_on_cluster

    with Client("tcp://scheduler:8786") as client:
        text = priors_on_cluster(folders, client)
    open("priors.json", "w").write(text)

Then `rccpack learn new-task/demos.json --priors priors.json`, or
`rccpack.learn(demos, priors="priors.json")`.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any, Union

from dask.distributed import Client

import rccpack

Folder = Union[str, "os.PathLike[str]"]


def gather_counts(
    folders: Sequence[Folder],
    client: Client,
    templates: str = "third",
    contact: str = "point",
) -> list[dict[str, Any]]:
    """Count every task folder on the cluster's workers, one task per
    folder; the counts come back in the order of `folders`. A folder that
    cannot be read raises here what `rccpack.task_counts` raises
    (`FileNotFoundError`, `rccpack.SceneError`, …)."""
    paths = [os.fspath(f) for f in folders]
    # pure=False: the result depends on the files, not only on the path.
    futures = client.map(
        rccpack.task_counts, paths, templates=templates, contact=contact, pure=False
    )
    counts: list[dict[str, Any]] = client.gather(futures)
    return counts


def priors_on_cluster(
    folders: Sequence[Folder],
    client: Client,
    strength: int = 4,
    rule_out_after: int = 10,
    templates: str = "third",
    contact: str = "point",
) -> str:
    """The priors file's text for the library `folders` (the defaults are
    those of `rccpack priors`)."""
    counts = gather_counts(folders, client, templates=templates, contact=contact)
    return rccpack.combine_priors(
        counts,
        strength=strength,
        rule_out_after=rule_out_after,
        templates=templates,
        contact=contact,
    )


if __name__ == "__main__":
    import sys

    from dask.distributed import LocalCluster

    # python dask_priors.py TASK_DIR... > priors.json (a local cluster)
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as c:
        sys.stdout.write(priors_on_cluster(sys.argv[1:], c))
