"""Command line: femcheck list | show | run | suite | bench | stress.

Exit codes: 0 every comparison passed, 1 a comparison failed or a model failed, 2 bad input (one line on
stderr naming the key and its allowed range; nothing written).
"""
from __future__ import annotations

import json
import sys
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator, List, Optional

import typer
from rich.console import Console
from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn
from rich.table import Table

from .errors import InputError

app = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="Cross-check fast contact models against FEM references.")
out_console = Console()
SCHEDULER_HELP = ("address of a dask.distributed scheduler (e.g. tcp://host:8786) to run the cases on; "
                  "default: local processes (needs the dist extra)")
if not out_console.is_terminal:       # piped or captured: do not wrap tables at 80 columns
    out_console = Console(width=220)
err_console = Console(stderr=True)


@contextmanager
def progress_bar(total: int | None, description: str) -> Iterator:
    """A rich progress bar on stderr (silent when stderr is not a terminal). Yields advance(text)."""
    prog = Progress(SpinnerColumn(), TextColumn("{task.description}"), BarColumn(), TimeElapsedColumn(),
                    console=err_console, transient=True, disable=not err_console.is_terminal)
    with prog:
        task = prog.add_task(description, total=total)

        def advance(text: str = "", step: int = 1) -> None:
            prog.update(task, advance=step, description=text or description)

        yield advance


def _scene(name: str, sets: list[str] | None, models: str | None = None):
    """The validated scene; ``--models`` replaces ``models.run`` before validation."""
    from .runner import resolve_scene
    from .scene import parse_overrides

    return resolve_scene(name, parse_overrides(sets or []), _models(models))


def _models(models: str | None) -> list[str] | None:
    return [m.strip() for m in models.split(",") if m.strip()] if models else None


def _write_json(path: Path, data) -> None:
    from .report.html import AtomicDir

    with AtomicDir(path.parent) as tmp:
        (tmp / path.name).write_text(json.dumps(data, indent=1))


def _print_run(res) -> None:
    t = Table(title=f"{res.scene}: models")
    for col in ("model", "status", "time (s)", "quantities", "note"):
        t.add_column(col)
    for name, m in res.models.items():
        q = "  ".join(f"{k}={v:.5g}" for k, v in m.quantities.items())
        t.add_row(name, m.status + (" (cached)" if m.cached else ""), f"{m.time_s:.3f}", q, m.error or "")
    out_console.print(t)
    c = Table(title="comparisons")
    for col in ("model", "reference", "quantity", "rel. error", "tolerance", "result"):
        c.add_column(col)
    for cmp in res.comparisons:
        verdict = "-" if cmp.passed is None else ("[green]pass[/]" if cmp.passed else "[red]FAIL[/]")
        tol = "-" if cmp.tolerance is None else f"{cmp.tolerance:.2%}"
        c.add_row(cmp.model, cmp.reference, cmp.quantity, f"{cmp.rel_error:.3%}", tol, verdict)
    out_console.print(c)


@app.command("list")
def list_scenes() -> None:
    """List the built-in scenes."""
    from .scene import builtin_scene_files, load_scene

    t = Table(title="femcheck scenes")
    for col in ("scene", "kind", "suites", "models", "description"):
        t.add_column(col)
    for name in builtin_scene_files():
        s = load_scene(name)
        t.add_row(name, s.kind, ", ".join(s.tags), ", ".join(s["models.run"]), " ".join(s.description.split()))
    out_console.print(t)


@app.command()
def show(scene: str = typer.Argument(..., help="scene name or TOML path"),
         set_: Optional[List[str]] = typer.Option(None, "--set", help="KEY=VALUE override")) -> None:
    """Show a scene's keys: value, unit, allowed range."""
    sc = _scene(scene, set_)
    out_console.print(f"[bold]{sc.name}[/] ({sc.kind}) - {' '.join(sc.description.split())}")
    t = Table()
    for col in ("key", "value", "unit", "allowed", "meaning"):
        t.add_column(col)
    from .scene import lookup_key

    for k, v in sc.params.items():
        spec = lookup_key(sc.schema, k)
        t.add_row(k, ", ".join(v) if isinstance(v, list) else f"{v:g}" if isinstance(v, float) else str(v),
                  spec.unit, spec.allowed(), spec.doc)
    out_console.print(t)


@app.command("run")
def run_cmd(scene: str = typer.Argument(..., help="scene name or TOML path"),
            set_: Optional[List[str]] = typer.Option(None, "--set", help="KEY=VALUE override (repeatable)"),
            models: Optional[str] = typer.Option(None, "--models", help="comma-separated models"),
            out: Optional[Path] = typer.Option(None, "--out", help="write the report (index.html, summary.json, figures) here"),
            json_out: bool = typer.Option(False, "--json", help="print one JSON object"),
            rebuild: bool = typer.Option(False, "--rebuild", help="ignore stored references and cached FEM results")) -> None:
    """Run one scene and compare its models."""
    from .runner import run

    sc = _scene(scene, set_, models)
    t0 = time.perf_counter()
    with progress_bar(None, sc.name) as advance:
        # a scene as shipped (no --set) is stored as a reference; one-off variations only go to the cache
        res = run(sc, rebuild=rebuild, progress=advance, store_references=not set_)
    if out is not None:
        from .report.html import write_report

        write_report([res], out, sc.name, time.perf_counter() - t0)
    if json_out:
        sys.stdout.write(json.dumps(res.to_json()) + "\n")
    else:
        _print_run(res)
    raise typer.Exit(0 if res.passed else 1)


@app.command()
def suite(name: str = typer.Argument(..., help="suite tag, e.g. quick"),
          out: Optional[Path] = typer.Option(None, "--out", help="report directory (default reports/NAME)"),
          rebuild: bool = typer.Option(False, "--rebuild", help="ignore stored references and cached FEM results")) -> None:
    """Run every scene tagged NAME and write DIR/index.html and DIR/summary.json. FEM references are taken
    from references/ when their provenance matches, else solved and stored there."""
    from .report.html import write_report
    from .runner import run
    from .scene import builtin_scene_files, load_scene

    scenes = [s for s in (load_scene(n) for n in builtin_scene_files()) if name in s.tags]
    if not scenes:
        tags = sorted({t for n in builtin_scene_files() for t in load_scene(n).tags})
        raise InputError("suite", f"no scene is tagged {name!r}; allowed: {', '.join(tags)}")
    out = out or Path("reports") / name
    t0 = time.perf_counter()
    runs = []
    with progress_bar(len(scenes), f"suite {name}") as advance:
        for sc in scenes:
            runs.append(run(sc, rebuild=rebuild, progress=lambda text: advance(text, 0), store_references=True))
            advance(sc.name)
    index = write_report(runs, out, name, time.perf_counter() - t0)
    for r in runs:
        _print_run(r)
    ok = all(r.passed for r in runs)
    out_console.print(f"{'PASS' if ok else 'FAIL'}: {len(runs)} scene(s) in {time.perf_counter() - t0:.1f} s; "
                      f"report {index}")
    raise typer.Exit(0 if ok else 1)


@app.command("bench")
def bench_cmd(scene: str = typer.Argument(..., help="scene name or TOML path"),
              set_: Optional[List[str]] = typer.Option(None, "--set", help="KEY=VALUE override"),
              models: Optional[str] = typer.Option(None, "--models", help="comma-separated models"),
              out: Optional[Path] = typer.Option(None, "--out", help="directory (default reports/bench-SCENE)"),
              scheduler: Optional[str] = typer.Option(None, "--scheduler", help=SCHEDULER_HELP)) -> None:
    """Time-vs-error sweep of each model's discretisation: table, bench.json, bench.csv, log-log plot."""
    from .bench import bench, scaling_exponent
    from .report import charts
    from .report.html import AtomicDir

    sc = _scene(scene, set_)
    out = out or Path("reports") / f"bench-{sc.name}"
    with progress_bar(None, f"bench {sc.name}") as advance:
        try:
            rows = bench(sc, _models(models), on_step=advance, scheduler=scheduler)
        except RuntimeError as err:
            out_console.print(f"[red]{err}[/]")
            raise typer.Exit(1)
    qnames = list(dict.fromkeys(k[4:] for r in rows for k in r if k.startswith("err_") and
                                not k.startswith("err_self_")))
    t = Table(title=f"{sc.name}: run time vs error (errors relative to {sc['models.references'][0]})")
    for col in ["model", "setting", "size", "iterations", "time (s)"] + [f"{q} err" for q in qnames]:
        t.add_column(col)
    for r in rows:
        setting = ", ".join(f"{k.split('.')[-1]}={v:g}" if isinstance(v, (int, float)) else f"{k.split('.')[-1]}={v}"
                            for k, v in r["setting"].items())
        errs = [f"{r['err_' + q]:.2e}" if "err_" + q in r else r.get("error", "-") for q in qnames]
        t.add_row(r["model"], setting, str(r.get("size", "-")), str(r.get("iterations", "-")),
                  f"{r['time_s']:.4f}", *errs)
    out_console.print(t)
    exps = {m: scaling_exponent(rows, m) for m in sorted({r["model"] for r in rows})}
    with AtomicDir(out) as tmp:
        (tmp / "bench.json").write_text(json.dumps({"scene": sc.name, "rows": rows, "time_vs_size_exponent": exps},
                                                   indent=1))
        cols = ["model", "setting", "size", "iterations", "time_s", "status"] + sorted(
            {k for r in rows for k in r if k.startswith("err_")})
        lines = [",".join(cols)] + [",".join(json.dumps(r.get(c, "")).replace(",", ";") for c in cols)
                                    for r in rows]
        (tmp / "bench.csv").write_text("\n".join(lines) + "\n")
        charts.time_error(rows, tmp / "bench.png", f"{sc.name}: run time vs error")
    for m, e in exps.items():
        if e is not None:
            out_console.print(f"{m}: time ~ size^{e:.2f}")
    out_console.print(f"written {out}/bench.json, bench.csv, bench.png")
    failed = [r for r in rows if r["status"] != "ok"]
    raise typer.Exit(1 if failed else 0)


@app.command("stress")
def stress_cmd(scene: str = typer.Argument(..., help="scene name or TOML path"),
               set_: Optional[List[str]] = typer.Option(None, "--set", help="KEY=VALUE override"),
               workers: Optional[int] = typer.Option(None, "--workers", help="worker processes"),
               out: Optional[Path] = typer.Option(None, "--out", help="directory (default reports/stress-SCENE)"),
               scheduler: Optional[str] = typer.Option(None, "--scheduler", help=SCHEDULER_HELP)) -> None:
    """Stability sweep over parameter extremes; lists every case that failed, was non-physical or inaccurate."""
    from .problems import problem
    from .report.html import AtomicDir
    from .stability import stress

    sc = _scene(scene, set_)
    out = out or Path("reports") / f"stress-{sc.name}"
    n = len(problem(sc.kind).stress_cases(sc))
    with progress_bar(n, f"stress {sc.name}") as advance:
        cases = stress(sc, workers, on_done=lambda i, c: advance(c.label), scheduler=scheduler)
    t = Table(title=f"{sc.name}: stability sweep ({len(cases)} cases)")
    models = sorted({m for c in cases for m in c.models})
    first = getattr(problem(sc.kind), "STRESS_QUANTITIES", ("p_max",))[0]
    for col in ["case", "status"] + [f"{m} {first} err" for m in models] + ["problems"]:
        t.add_column(col)
    for c in cases:
        colour = {"ok": "green", "refused": "yellow"}.get(c.status, "red")
        errs = [f"{c.models[m]['err_' + first]:.1e}" if "err_" + first in c.models.get(m, {}) else
                c.models.get(m, {}).get("status", "-") for m in models]
        t.add_row(c.label, f"[{colour}]{c.status}[/]", *errs, "; ".join(c.problems))
    out_console.print(t)
    bad = [c for c in cases if c.status in ("failed", "inaccurate")]
    with AtomicDir(out) as tmp:
        (tmp / "stress.json").write_text(json.dumps({"scene": sc.name, "cases": [c.to_json() for c in cases],
                                                    "failures": [c.label for c in bad]}, indent=1))
    out_console.print(f"{len(bad)} of {len(cases)} cases failed or were inaccurate; written {out}/stress.json")
    raise typer.Exit(1 if bad else 0)


@app.command("map")
def map_cmd(scene: str = typer.Argument(..., help="scene name or TOML path"),
            x: str = typer.Option(..., "--x", help="KEY=lo:hi:n[:log|:lin], the horizontal axis"),
            y: str = typer.Option(..., "--y", help="KEY=lo:hi:n[:log|:lin], the vertical axis"),
            set_: Optional[List[str]] = typer.Option(None, "--set", help="KEY=VALUE override"),
            models: Optional[str] = typer.Option(None, "--models", help="comma-separated models"),
            workers: Optional[int] = typer.Option(None, "--workers", help="worker processes"),
            scheduler: Optional[str] = typer.Option(None, "--scheduler", help=SCHEDULER_HELP),
            out: Optional[Path] = typer.Option(None, "--out", help="directory (default reports/map-SCENE)")) -> None:
    """Validity map: run the scene over a grid of two keys; heat maps of each model's error against each
    reference with the region inside tolerance outlined, map.json, and plain statements of where each model
    may be used. Exit 1 if a model failed at some grid point."""
    from .report.html import write_map_report
    from .validity_map import parse_axis, validity_map

    sc = _scene(scene, set_, models)
    ax, ay = parse_axis("--x", x, sc), parse_axis("--y", y, sc)
    names = _models(models)
    out = out or Path("reports") / f"map-{sc.name}"
    t0 = time.perf_counter()
    with progress_bar(len(ax.values) * len(ay.values), f"map {sc.name}") as advance:
        vmap = validity_map(sc, ax, ay, names, workers, scheduler,
                            on_done=lambda i, p: advance(f"{p.overrides} {p.status}"))
    index = write_map_report(vmap, out, time.perf_counter() - t0)
    for line in vmap.statements():
        out_console.print(f"- {line}")
    out_console.print(f"written {index}, {out}/map.json")
    raise typer.Exit(1 if any(p.status == "failed" for p in vmap.points) else 0)


@app.command()
def calibrate(scene: str = typer.Argument(..., help="scene whose kind has a calibrated model"),
              set_: Optional[List[str]] = typer.Option(None, "--set", help="KEY=VALUE override"),
              out: Optional[Path] = typer.Option(None, "--out", help="JSON file (default: the packaged one)"))\
        -> None:
    """Recalibrate a semi-analytic model against the scene's numerical reference and store its coefficients."""
    from .problems import problem

    sc = _scene(scene, set_)
    prob = problem(sc.kind)
    if not hasattr(prob, "calibrate"):
        raise InputError("scene", f"kind {sc.kind} has no calibrated model")
    with progress_bar(None, f"calibrate {sc.name}") as advance:
        data = prob.calibrate(sc, progress=advance)
    target = out or prob.CALIBRATION_FILE
    _write_json(target, data)
    pv = data["provenance"]
    out_console.print({k: v for k, v in data.items() if k != "provenance"})
    out_console.print(f"misfit to the calibration samples: max {pv['max_rel_misfit']:.2%}, "
                      f"rms {pv['rms_rel_misfit']:.2%}; written {target}")


def main() -> None:
    try:
        app()
    except InputError as err:
        print(f"femcheck: error: {err}", file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()
