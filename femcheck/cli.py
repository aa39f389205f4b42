"""Command line: femcheck list | show | run | suite | bench | stress | map | calibrate | export.

Exit codes: 0 every comparison passed, 1 a comparison failed or a model failed, 2 bad input (one line on
stderr naming the key and its allowed range; nothing written).
"""
from __future__ import annotations

import json
import os
import sys
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator, List, Optional

import typer
from rich.console import Console
from rich.progress import (BarColumn, MofNCompleteColumn, Progress, SpinnerColumn, TextColumn,
                           TimeElapsedColumn)
from rich.table import Table

from .errors import InputError

app = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="Cross-check fast contact models against FEM references.")


def _version(value: bool) -> None:
    if value:
        from . import __version__

        print(f"femcheck {__version__}")
        raise typer.Exit(0)


@app.callback()
def _root(version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                       help="print the version and exit")) -> None:
    """Cross-check fast contact models against FEM references."""
out_console = Console()
SCHEDULER_HELP = ("address of a dask.distributed scheduler (e.g. tcp://host:8786) to run the cases on; "
                  "default: local processes (needs the dist extra)")
RUN_SCHEDULER_HELP = "dask.distributed scheduler (tcp://host:8786) for a reference's independent FE levels"
if not out_console.is_terminal:       # piped or captured: do not wrap tables at 80 columns
    out_console = Console(width=220)
err_console = Console(stderr=True)


@contextmanager
def progress_bar(total: int | None, description: str) -> Iterator:
    """A rich progress bar on stderr (silent when stderr is not a terminal). Yields advance(text); its
    ``log(line)`` prints a line above the bar (and to stderr when it is not a terminal)."""
    prog = Progress(SpinnerColumn(), TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                    TimeElapsedColumn(), console=err_console, transient=True, disable=not err_console.is_terminal)
    with prog:
        task = prog.add_task(description, total=total)

        def advance(text: str = "", step: int = 1) -> None:
            prog.update(task, advance=step, description=text or description)

        advance.log = prog.console.print
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
    from .result import dumps

    with AtomicDir(path.parent) as tmp:
        (tmp / path.name).write_text(dumps(data, indent=1))


VERDICT_STYLE = {"valid": "green", "contrast": "dim", "not valid here": "red", "reference uncertified": "yellow",
                 "ungraded": "magenta", "failed": "bold red", "skipped": "dim", "reference": "blue",
                 "not compared": "blue"}


def _verdict(v: str, contrast: bool = False) -> str:
    text = v + (" (contrast)" if contrast and v == "not valid here" else "")
    return f"[{VERDICT_STYLE.get(v, 'white')}]{text}[/]"


def _quantity(name: str, value: float, params: dict, kind: str) -> str:
    """``name=value unit`` for the terminal (unit from :func:`femcheck.report.units.unit_of`)."""
    from .report.units import unit_of

    unit = unit_of(name, params, kind)
    return f"{name}={value:.5g}" + ("" if unit in ("-", "") else f" {unit}")


def conclusion(res, elapsed_s: float, written: str | None) -> tuple[str, int]:
    """The closing line of ``femcheck run`` and its exit code: PASS (0) / FAIL (1) with the counts of each
    verdict, or NOTHING COMPARED (1: a run that checked nothing must not look like a pass), then the time and
    where the report went (or how to write one)."""
    counts: dict[str, int] = {}
    for c in res.comparisons:
        key = "contrast outside its band" if c.verdict == "not valid here" and c.contrast else c.verdict
        counts[key] = counts.get(key, 0) + 1
    tail = f"; {len(res.models)} model(s) in {elapsed_s:.1f} s; " + (
        written or "nothing written (--out DIR writes the report, --json prints the results)")
    if not res.comparisons:
        refs = ", ".join(res.params.get("models.references", ()))
        why = "; ".join(f"{n} {m.status}" + (f": {m.error}" if m.error else "") for n, m in res.models.items()
                        if n in res.params.get("models.references", ()) and m.status != "ok")
        return (f"NOTHING COMPARED: no reference ran (models.references: {refs}"
                + (f"; {why}" if why else "") + ")" + tail), 1
    order = ("valid", "contrast", "reference uncertified", "contrast outside its band", "not valid here", "ungraded")
    parts = ", ".join(f"{counts[v]} {v}" for v in order[1:] if counts.get(v))
    head = res.verdict
    if head == "INFORMATIONAL":
        return f"INFORMATIONAL: only contrast models compared, none claimed valid here ({parts})" + tail, 0
    text = f"{head}: {counts.get('valid', 0)} of {len(res.comparisons)} comparisons valid" + (
        f" ({parts})" if parts else "")
    failed = [n for n, m in res.models.items() if m.status == "failed"]
    if failed:
        text += f"; failed: {', '.join(failed)}"
    return text + tail, 0 if res.passed else 1


def _print_run(res) -> None:
    t = Table(title=f"{res.scene}: models")
    for col in ("model", "status", "time (s)", "quantities (SI)", "note"):
        t.add_column(col)
    for name, m in res.models.items():
        q = "  ".join(_quantity(k, v, res.params, res.kind) for k, v in m.quantities.items())
        t.add_row(name, m.status + (" (cached)" if m.cached else ""), f"{m.time_s:.3f}", q, m.error or "")
    out_console.print(t)
    if not res.comparisons:
        return
    c = Table(title="comparisons")
    for col in ("model", "reference", "quantity", "rel. error", "tolerance", "verdict", "note"):
        c.add_column(col)
    for cmp in res.comparisons:
        tol = "-" if cmp.tolerance is None else f"{cmp.tolerance:.3g}"
        c.add_row(cmp.model, cmp.reference, cmp.quantity, f"{cmp.rel_error:.3g}", tol,
                  _verdict(cmp.verdict, cmp.contrast), cmp.note)
    out_console.print(c)
    for p in res.problems:
        out_console.print(f"[red]{res.scene}: {p}[/]")


def _scene_verdict(v: str) -> str:
    return f"[{ {'PASS': 'green', 'INFORMATIONAL': 'blue'}.get(v, 'red') }]{v}[/]"


def _print_dashboard(runs) -> None:
    """The suite's validity dashboard: one row per scene and model (the report's table)."""
    from .report.dashboard import rows

    def shown(c) -> str:
        return f"{c.rel_error:.2g} {c.quantity}" + ("" if c.tolerance is None else f" (tol {c.tolerance:.2g})")

    t = Table(title="validity: one verdict per reference; the design quantity's error, and the worst if another")
    for col in ("scene", "model", "role", "error against each reference", "verdict", "run time"):
        t.add_column(col)
    for run in runs:
        for i, r in enumerate(rows(run)):
            errors = "\n".join(f"{rv.reference}: " + "; ".join(shown(c) for c in rv.shown) for rv in r.per_reference)
            verdicts = "\n".join(_verdict(rv.verdict, r.role == "contrast") for rv in r.per_reference)
            scene = f"{run.scene} {_scene_verdict(run.verdict)}" if i == 0 else ""
            t.add_row(scene, r.model, r.role, errors or r.note, verdicts or _verdict(r.verdict), r.time_text,
                      end_section=i == len(run.models) - 1)
    out_console.print(t)


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
            rebuild: bool = typer.Option(False, "--rebuild", help="ignore stored references and cached FEM results"),
            references: Optional[Path] = typer.Option(None, "--references", help="directory where the FE "
                                                      "references of your scene are kept (read and written); "
                                                      "without it they stay in the cache"),
            scheduler: Optional[str] = typer.Option(None, "--scheduler", help=RUN_SCHEDULER_HELP)) -> None:
    """Run one scene and compare its models."""
    from .executor import check_scheduler, remote
    from .runner import run

    sc = _scene(scene, set_, models)
    if scheduler:
        check_scheduler(scheduler)
    t0 = time.perf_counter()
    with progress_bar(None, sc.name) as advance, remote(scheduler):
        # a built-in scene as shipped (no --set) is stored with the package's references; a user's scene only in
        # the directory the user names; one-off variations only go to the cache
        store = references is not None or (sc.builtin and not set_)
        res = run(sc, rebuild=rebuild, progress=advance, store_references=store, references_dir=references)
    written = None
    if out is not None:
        from .report.html import write_report

        written = f"report {write_report([res], out, sc.name, time.perf_counter() - t0)}"
    line, code = conclusion(res, time.perf_counter() - t0, written)
    if json_out:
        from .result import dumps

        sys.stdout.write(dumps(res.to_json()) + "\n")
        err_console.print(line, highlight=False, soft_wrap=True)
    else:
        _print_run(res)
        out_console.print(f"{_scene_verdict(line.partition(':')[0])}:{line.partition(':')[2]}", highlight=False,
                          soft_wrap=True)
    raise typer.Exit(code)


@app.command()
def suite(name: str = typer.Argument(..., help="suite tag, e.g. quick"),
          out: Optional[Path] = typer.Option(None, "--out", help="report directory (default reports/NAME)"),
          rebuild: bool = typer.Option(False, "--rebuild", help="ignore stored references and cached FEM results")) -> None:
    """Run every scene tagged NAME and write DIR/index.html and DIR/summary.json. FEM references are taken
    from references/ when their provenance matches, else solved and stored there."""
    from .scene import builtin_tags, did_you_mean, load_scene

    tagged = [n for n, tags in builtin_tags().items() if name in tags]     # no scene built: a bad name fails fast
    if not tagged:
        tags = sorted({t for ts in builtin_tags().values() for t in ts})
        raise InputError("suite", f"no scene is tagged {name!r}{did_you_mean(name, tags)}; allowed: "
                                  f"{', '.join(tags)}")
    from .report.html import write_report
    from .runner import run

    scenes = [load_scene(n) for n in tagged]
    out = out or Path("reports") / name
    t0 = time.perf_counter()
    runs = []
    with progress_bar(len(scenes), f"suite {name}") as advance:
        for sc in scenes:
            runs.append(run(sc, rebuild=rebuild, progress=lambda text: advance(text, 0), store_references=True))
            advance(sc.name)
    t_scenes = time.perf_counter() - t0
    index = write_report(runs, out, name, t_scenes)
    t_report = time.perf_counter() - t0 - t_scenes
    _print_dashboard(runs)
    failed = [r for r in runs if not r.passed]
    for r in failed:
        for p in r.problems:
            out_console.print(f"[red]{r.scene}: {p}[/]")
    verdict = "PASS" if not failed else f"FAIL: {len(failed)} of {len(runs)} scene(s) failed " \
        f"({', '.join(r.scene for r in failed)})"
    out_console.print(f"{verdict}; {len(runs)} scene(s) in {t_scenes:.1f} s, report written in {t_report:.1f} s: "
                      f"{index}")
    raise typer.Exit(0 if not failed else 1)


@app.command("bench")
def bench_cmd(scene: str = typer.Argument(..., help="scene name or TOML path"),
              set_: Optional[List[str]] = typer.Option(None, "--set", help="KEY=VALUE override"),
              models: Optional[str] = typer.Option(None, "--models", help="comma-separated models"),
              out: Optional[Path] = typer.Option(None, "--out", help="directory (default reports/bench-SCENE)"),
              scheduler: Optional[str] = typer.Option(None, "--scheduler", help=SCHEDULER_HELP)) -> None:
    """Time-vs-error sweep of each model's discretisation: table, bench.json, bench.csv, log-log plot."""
    from .bench import bench, scaling_exponent
    from .result import dumps
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
        (tmp / "bench.json").write_text(dumps({"scene": sc.name, "rows": rows, "time_vs_size_exponent": exps},
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
               models: Optional[str] = typer.Option(None, "--models", help="comma-separated models (default: "
                                                     "models.run without the FE references)"),
               workers: Optional[int] = typer.Option(None, "--workers", help="worker processes"),
               out: Optional[Path] = typer.Option(None, "--out", help="directory (default reports/stress-SCENE)"),
               scheduler: Optional[str] = typer.Option(None, "--scheduler", help=SCHEDULER_HELP)) -> None:
    """Stability sweep over parameter extremes; lists every case that failed, was non-physical, inaccurate or
    compared with nothing. FE references run only when --models names them (minutes and GB per case)."""
    from .problems import problem
    from .report.html import AtomicDir
    from .result import dumps
    from .stability import default_models, stress

    sc = _scene(scene, set_, models)
    names = _models(models) or default_models(sc)
    out = out or Path("reports") / f"stress-{sc.name}"
    prob = problem(sc.kind)
    n = len(prob.stress_cases(sc))
    left_out = [m for m in sc["models.run"] if m not in names]
    out_console.print(f"stress {sc.name}: {n} cases, models {', '.join(names)}"
                      + (f" (left out: {', '.join(left_out)}; --models to add them)" if left_out else ""))
    first = getattr(prob, "STRESS_QUANTITIES", ("p_max",))[0]
    done = [0]
    with progress_bar(n, f"stress {sc.name}") as advance:
        def on_done(i, c):
            done[0] += 1
            colour = {"ok": "green", "refused": "yellow", "unchecked": "yellow"}.get(c.status, "red")
            t = sum(m.get("time_s", 0.0) for m in c.models.values())
            errs = ", ".join(f"{m} {first} {v['err_' + first]:.1e}" for m, v in c.models.items()
                             if "err_" + first in v)
            advance.log(f"[{done[0]:>{len(str(n))}}/{n}] {c.label}: [{colour}]{c.status}[/] ({t:.2f} s)"
                        + (f" {errs}" if errs else "") + (f" - {'; '.join(c.problems)}" if c.problems else ""))
            advance(c.label)

        cases = stress(sc, workers, on_done=on_done, scheduler=scheduler, models=names)
    t = Table(title=f"{sc.name}: stability sweep ({len(cases)} cases)")
    shown = sorted({m for c in cases for m in c.models})
    for col in ["case", "status"] + [f"{m} {first} err" for m in shown] + ["problems"]:
        t.add_column(col)
    for c in cases:
        colour = {"ok": "green", "refused": "yellow", "unchecked": "yellow"}.get(c.status, "red")
        errs = [f"{c.models[m]['err_' + first]:.1e}" if "err_" + first in c.models.get(m, {}) else
                c.models.get(m, {}).get("status", "-") for m in shown]
        t.add_row(c.label, f"[{colour}]{c.status}[/]", *errs, "; ".join(c.problems))
    out_console.print(t)
    bad = [c for c in cases if c.status in ("failed", "inaccurate")]
    unchecked = [c for c in cases if c.status == "unchecked"]
    with AtomicDir(out) as tmp:
        (tmp / "stress.json").write_text(dumps({"scene": sc.name, "models": names,
                                                    "cases": [c.to_json() for c in cases],
                                                    "failures": [c.label for c in bad],
                                                    "unchecked": [c.label for c in unchecked]}, indent=1))
    out_console.print(f"{len(bad)} of {len(cases)} cases failed or were inaccurate, {len(unchecked)} compared with "
                      f"no reference; written {out}/stress.json")
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


@app.command("export")
def export_cmd(scene: str = typer.Argument(..., help="scene name or TOML path (kinds: point_contact, line_contact, "
                                                  "roller_contact, srb_contact, layer_contact, line_tangential, "
                                                  "bearing_load)"),
               fmt: str = typer.Option(..., "--format", help="calculix or abaqus"),
               level: int = typer.Option(0, "--level", help="mesh level of the scene's FE family (0 = coarsest)"),
               order: int = typer.Option(2, "--order", help="element order: 1 linear (C3D4/CPE3), 2 quadratic "
                                                          "(C3D10/CPE6)"),
               out: Path = typer.Option(..., "--out", help="directory the deck is written to"),
               set_: Optional[List[str]] = typer.Option(None, "--set", help="KEY=VALUE override")) -> None:
    """Write the scene's FE reference as an Abaqus / CalculiX input deck (femcheck's own mesh, rigid indenter or
    meshed bodies, node-to-surface penalty contact, load steps under load control); the heading says which
    outputs give the contact pressure."""
    from .export.write import export

    sc = _scene(scene, set_)
    info = export(sc, fmt.lower(), level, order, out)
    out_console.print(f"written {info['deck']}: {info['element']}, level {info['level']} (h = "
                      f"{info['h_over_a']:.4g} a), {info['block_nodes']} deformable nodes, {info['block_dofs']} DOFs;"
                      f" run: ccx -i {Path(info['deck']).with_suffix('')}", highlight=False, soft_wrap=True)


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
    if out is None and not sc.builtin:      # never write a user's calibration into the installed package
        raise InputError("--out", f"{sc.source} is not a built-in scene: say where its calibration goes "
                                  "(--out FILE)")
    target = out or prob.CALIBRATION_FILE
    _write_json(target, data)
    pv = data["provenance"]
    out_console.print({k: v for k, v in data.items() if k != "provenance"})
    out_console.print(f"misfit to the calibration samples: max {pv['max_rel_misfit']:.2%}, "
                      f"rms {pv['rms_rel_misfit']:.2%}; written {target}")


def main() -> None:
    import signal

    from .executor import Interrupted, stop_on_signals

    try:
        with stop_on_signals((signal.SIGINT, signal.SIGTERM)):
            app()
    except InputError as err:
        print(f"femcheck: error: {err}", file=sys.stderr)
        sys.exit(2)
    except (Interrupted, KeyboardInterrupt) as err:
        signum = getattr(err, "signum", signal.SIGINT)
        print(f"femcheck: interrupted ({signal.Signals(signum).name}): stopped, workers ended, nothing written",
              file=sys.stderr)
        sys.stdout.flush()
        sys.stderr.flush()
        # the workers are ended and nothing is left to write: skip the interpreter's exit hooks, of which
        # concurrent.futures' may write to the stopped pool's closed wakeup pipe and print a traceback
        os._exit(128 + signum)


if __name__ == "__main__":
    main()
