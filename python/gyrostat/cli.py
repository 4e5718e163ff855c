"""The command line: ``gyrostat run SCENE.toml``, ``gyrostat sweep SCENE.toml --vary ...``,
``gyrostat check SCENE.toml``, ``gyrostat examples``, ``gyrostat methods``, ``gyrostat
scene-format``; ``gyrostat --version``. Also ``python -m gyrostat``. A scene with a ``[sweep]``
table runs its sweep too. A scene runs code only from its own folder and the modules given with
``--allow-import`` (:mod:`gyrostat.scene_code`).

Exit codes: 0 every scene ran and succeeded (``check``: every scene is valid); 1 a run failed (its
partial results are written); 2 a scene file is wrong (a one-line message names the key and the
table, no traceback)."""

from __future__ import annotations

import argparse
import html
import os
import sys
from importlib import resources
from pathlib import Path


ALLOW_HELP = ("a module (package) whose code the scene may name in a user torque, with every module below it; "
              "repeat for several (the scene's own folder is always allowed; nothing else is)")


def example_scenes() -> list[Path]:
    """The scenes shipped with the package."""
    folder = resources.files("gyrostat") / "scenes"
    return sorted(Path(str(p)) for p in folder.iterdir() if p.name.endswith(".toml"))


def _changes(entries: dict) -> str:
    """``name +1.2e-09`` (relative change) or ``name 3.4e-12 (absolute)`` where a relative
    change means nothing (the quantity starts at zero)."""
    return ", ".join(f"{k} {v['relative_change']:+.3e}" if "relative_change" in v else
                     f"{k} {v['max_abs_change']:.3e} (absolute)" for k, v in entries.items()
                     if v.get("relative_change", v.get("max_abs_change")) is not None)


def _print_report(report: dict) -> None:
    print(f"{report['scene']}: {report['title']}")
    total = report.get("seconds_total")
    print(f"  model: {report['model']} ({report['model_reason']}); status: {report['status']}; "
          f"solving took {report['seconds']:.3g} s"
          + (f" ({total:.3g} s with the checks, files and plots)" if total is not None else ""))
    if "ladder" in report:
        ladder = report["ladder"]
        switches = ladder["switches"]
        print(f"  ladder (accuracy {ladder['accuracy']:g}): {ladder['summary']}"
              + (f"; {len(switches)} switch(es)" if switches else ""))
        for switch in switches[:6]:
            print(f"    t = {switch['t']:.6g}: {switch['from']} -> {switch['to']} ({switch['reason']})")
    for name, run in report.get("runs", {}).items():
        stats = run["stats"]
        kept, changed = _changes(run["conserved"]), _changes(run.get("changed_by_torques", {}))
        used = f" ({' then '.join(run['methods_used'])})" if run.get("methods_used") else ""
        print(f"  {name}: {run['method']}{used}, {run['status']}; steps {stats['steps']}, rhs evaluations "
              f"{stats['rhs_evals']}, rejected {stats['rejected_steps']}")
        if kept:
            print(f"    conserved, relative change from t0 to the end (integration error): {kept}")
        if changed:
            print(f"    changed by the torques, relative change from t0 to the end: {changed}")
        for switch in run.get("method_switches", [])[:4]:
            print(f"    t = {switch['t']:.6g}: -> {switch['to']} ({switch['reason']})")
        for event, times in run.get("events", {}).items():
            shown = ", ".join(f"{t:.6g}" for t in times[:5]) + (", ..." if len(times) > 5 else "")
            print(f"    event {event}: {len(times)} crossing(s)" + (f" at t = {shown}" if times else ""))
        if run["message"]:
            print(f"    message: {run['message']}")
    for key, diff in report.items():  # averaged_vs_full and its variants: name → max difference
        if key.startswith("averaged_vs_full") and isinstance(diff, dict):
            text = ", ".join(f"{name} {value:.3e}" for name, value in diff.items() if isinstance(value, float))
            print(f"  averaged vs full: {text}")
    for broken in report.get("unexpected_broken", report.get("broken_assumptions", [])):
        print(f"  WARNING assumption broken: {broken}")
    for expected in report.get("expected_broken", []):
        print(f"  expected, the scene breaks it on purpose: {expected['assumption']}")
        print(f"    why: {' '.join(expected['why'].split())}")
    if report.get("expected_broken") and report.get("agreement"):
        print(f"    measured: {report['agreement']}")
    for held in report.get("expected_but_held", []):
        print(f"  NOTE the scene expects '{held}' to break, but it holds: its [[expected_broken]] entry is stale")
    for doubt in report.get("accuracy_warnings", []):
        print(f"  WARNING accuracy: {doubt}")
    for plot in report.get("plots_skipped", []):
        print(f"  WARNING plot '{plot['plot']}' not drawn: {plot['reason']}")
    if "max_error_vs_closed_form" in report:
        print(f"  max |omega - closed form| = {report['max_error_vs_closed_form']:.3e}")
    for f in report.get("files", []):
        print(f"  wrote {f}")


def _print_sweep(report: dict) -> None:
    statuses = ", ".join(f"{count} {status}" for status, count in report["statuses"].items())
    print(f"{report['scene']}: sweep of {report['members']} members ({report['mode']}"
          + (f", seed {report['seed']}" if report["seed"] is not None else "") + f"), run {report['run']}")
    print(f"  {statuses}; {report['seconds']:.3g} s ({report['members_per_second']:.3g} members/s)")
    if report["summary_range"]:
        print(f"  {report['summary']}: from {report['summary_range'][0]:.6g} to {report['summary_range'][1]:.6g}")
    unexpected = report.get("unexpected_broken", report["broken_assumptions"])
    if report["members_with_broken_assumptions"] and unexpected:
        print(f"  WARNING {report['members_with_broken_assumptions']} member(s) break an assumption of their model: "
              + "; ".join(unexpected[:3]) + (" ..." if len(unexpected) > 3 else ""))
    elif report["members_with_broken_assumptions"]:
        print(f"  expected: {report['members_with_broken_assumptions']} member(s) break only the assumptions the scene "
              f"expects to break ({'; '.join(sorted(set(report.get('expected_parts', []))))})")
    if report["members_with_accuracy_warnings"]:
        print(f"  WARNING {report['members_with_accuracy_warnings']} member(s) doubt their own answer: "
              + report["accuracy_warnings"][0] + (" ..." if len(report["accuracy_warnings"]) > 1 else ""))
    if report["interrupted"]:
        print("  interrupted: the members not finished have status 'interrupted'")
    for f in report["files"]:
        print(f"  wrote {f}")


def _one_line(error: BaseException) -> str:
    """An exception as one line: its type where it is not a plain input error, its message, its notes."""
    text = " ".join(str(error).split())
    if not isinstance(error, (ValueError, TypeError, OSError)):
        text = f"{type(error).__name__}: {text}" if text else type(error).__name__
    notes = getattr(error, "__notes__", None) or []
    return "; ".join([text, *(" ".join(str(note).split()) for note in notes)])


def _code_names(scene) -> str:
    """``'m:f', 'm:g'``: the code a scene names (its user torques' functions), or nothing."""
    names = sorted({str(entry[key]) for entry in scene.doc.get("torques", [])
                    for key in ("function", "jacobian") if key in entry})
    return ", ".join(repr(name) for name in names)


def _check(args) -> int:
    """``gyrostat check``: every scene validated as ``run`` would, its code neither imported nor
    called; exit 0 when all are valid, 2 otherwise."""
    from gyrostat.scene import Scene

    bad = 0
    for path in args.scenes:
        try:
            scene = Scene.from_file(path, allow_import=args.allow_import, check_only=True)
        except KeyboardInterrupt:
            print(f"{path}: interrupted", file=sys.stderr)
            return 130
        except Exception as error:  # noqa: BLE001 - the scene is wrong: one line, never a traceback
            print(f"{path}: error: {_one_line(error)}", file=sys.stderr)
            bad += 1
            continue
        runs = ", ".join(f"{run.name} ({type(run.model).__name__}, t = {run.t_span[0]:g}..{run.t_span[1]:g})"
                         for run in scene.runs)
        code = f"; names code (not imported by the check): {_code_names(scene)}" if scene.names_code else ""
        print(f"{path}: ok: kind {scene.kind.name}, runs {runs}"
              + (f", model chosen by the ladder when run" if scene.ladder is not None else "") + code)
    return 2 if bad else 0


def _sweep(args) -> int:
    """``gyrostat sweep``: exit 0 when every member ran (failed members are recorded in
    sweep.nc and counted on the summary line), 2 for a wrong scene or --vary, 130 on Ctrl-C."""
    import warnings

    from gyrostat import output
    from gyrostat.runner import run_sweep
    from gyrostat.schema import SceneError
    from gyrostat.sweeps import parameter_from_text

    client = None
    try:
        vary = [parameter_from_text(text) for text in args.vary] if args.vary else None
        output.claim_folder(args.out / args.scene.stem, args.overwrite, what="sweep")
        if args.dask:
            from distributed import Client

            try:
                client = Client(args.dask, timeout="10s")
            except (OSError, TimeoutError) as error:
                print(f"--dask {args.dask}: cannot reach the scheduler: {error}", file=sys.stderr)
                return 2
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # an interrupted sweep: in its report
            report = run_sweep(args.scene, args.out, vary, samples=args.samples, seed=args.seed, run=args.run,
                               trajectories=True if args.trajectories else None, summary=args.summary, client=client,
                               threads=args.threads, workers=args.workers, chunk_size=args.chunk_size,
                               progress=False if args.quiet else None, allow_import=args.allow_import)
    except KeyboardInterrupt:
        print(f"{args.scene}: interrupted", file=sys.stderr)
        return 130
    except SceneError as error:
        print(f"{args.scene}: error: {error}", file=sys.stderr)
        return 2
    except Exception as error:  # noqa: BLE001 - one line, never a traceback
        print(f"{args.scene}: error: {_one_line(error)}", file=sys.stderr)
        return 2
    finally:
        if client is not None:
            client.close()
    _print_sweep(report)
    return 130 if report["interrupted"] else 0


SUMMARY_COLUMNS = ("scene", "model", "verdict", "time [s]", "folder")


def _summary_row(report: dict, out: Path) -> tuple[str, ...]:
    return (report["scene"], report["model"], report["verdict"], f"{report.get('seconds_total', report['seconds']):.3g}",
            str(Path(report.get("folder", out / report["scene"]))))


def _print_summary(rows: list[tuple[str, ...]]) -> None:
    """The table that ends a run of several scenes: scene, model chosen, verdict, time, folder."""
    widths = [max(len(r[i]) for r in [SUMMARY_COLUMNS, *rows]) for i in range(len(SUMMARY_COLUMNS))]
    print("\nsummary (time: solving, checks, files and plots)")
    for row in [SUMMARY_COLUMNS, tuple("-" * w for w in widths), *rows]:
        print("  " + "  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip())


def write_index(out: Path) -> list[Path]:
    """OUT/index.html and OUT/index.md: every scene folder in OUT with a report.json, its title,
    model, verdict and time, linked to its report and its plots (the HTML shows the plots)."""
    import json

    out = Path(out)
    entries = []
    for report_path in sorted(out.glob("*/report.json")):
        try:
            report = json.loads(report_path.read_text())
        except (OSError, ValueError):
            continue
        folder = report_path.parent
        entries.append((folder.name, report, sorted(p.name for p in folder.glob("*.png"))))
    md = ["# gyrostat results", "", "| scene | model | verdict | time [s] | report | plots |", "|---|---|---|---|---|---|"]
    page = ["<!doctype html><meta charset='utf-8'><title>gyrostat results</title>",
            "<style>body{font-family:sans-serif;max-width:1200px;margin:auto}img{width:380px;margin:4px;"
            "border:1px solid #ccc}td,th{padding:2px 8px;text-align:left}</style><h1>gyrostat results</h1><table>",
            "<tr><th>scene</th><th>model</th><th>verdict</th><th>time [s]</th></tr>"]
    for name, report, images in entries:
        verdict = report.get("verdict", report.get("status", ""))
        seconds = f"{report.get('seconds_total', report.get('seconds', float('nan'))):.3g}"
        links = ", ".join(f"[{image}]({name}/{image})" for image in images)
        md.append(f"| {name} | {report.get('model', '')} | {verdict} | {seconds} | [report.json]({name}/report.json) "
                  f"| {links} |")
        page.append(f"<tr><td><a href='#{html.escape(name)}'>{html.escape(name)}</a></td><td>"
                    f"{html.escape(report.get('model', ''))}</td><td>{html.escape(verdict)}</td><td>{seconds}</td></tr>")
    page.append("</table>")
    for name, report, images in entries:
        page.append(f"<h2 id='{html.escape(name)}'>{html.escape(name)}: {html.escape(report.get('title', ''))}</h2>")
        page.append(f"<p>{html.escape(report.get('verdict', ''))}; <a href='{html.escape(name)}/report.json'>"
                    "report.json</a></p>")
        for expected in report.get("expected_broken", []):
            page.append(f"<p>expected: {html.escape(expected['assumption'])}<br>why: {html.escape(expected['why'])}</p>")
        page += [f"<a href='{html.escape(name)}/{html.escape(i)}'><img src='{html.escape(name)}/{html.escape(i)}' "
                 f"alt='{html.escape(i)}'></a>" for i in images]
    (out / "index.md").write_text("\n".join(md) + "\n")
    (out / "index.html").write_text("\n".join(page) + "\n")
    return [out / "index.html", out / "index.md"]


RUN_DESCRIPTION = """Solves each scene file and writes its results to OUT/<scene>/ (<scene>: the file's
name without .toml): result.csv and result.npz (t, the state and every output, with units),
the plots the scene asks for (PNG) and report.json (method, statistics, conserved quantities,
assumptions checked, events). Several scenes end with a summary table; OUT/index.html and
OUT/index.md link every scene's plots and report. A scene with a [sweep] table runs its sweep too.
The scene format: gyrostat scene-format."""
RUN_EXAMPLE = """example:
  gyrostat run my_scene.toml --out results     # results/my_scene/{result.csv,report.json,*.png}
  gyrostat run a.toml b.toml --out results --overwrite

exit status: 0 every scene ran and succeeded, 1 a run failed (its partial results are written),
2 a scene file is wrong (a one-line message names the key)."""


def main(argv: list[str] | None = None) -> int:
    """The command line; output cut short by a closed pipe (``gyrostat scene-format | head``)
    ends quietly."""
    try:
        return _main(argv)
    except BrokenPipeError:
        # the reader left: send what is still buffered nowhere, so that the exit does not fail again
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0


def _main(argv: list[str] | None = None) -> int:
    from gyrostat import __version__

    parser = argparse.ArgumentParser(prog="gyrostat", description="Perturbed rotation of rigid bodies and gyrostats.")
    parser.add_argument("--version", action="version", version=f"gyrostat {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="solve one or more scene files, save results and plots in OUT/<scene>/",
                         description=RUN_DESCRIPTION, epilog=RUN_EXAMPLE,
                         formatter_class=argparse.RawDescriptionHelpFormatter)
    run.add_argument("scenes", nargs="+", type=Path, help="scene files (TOML)")
    run.add_argument("--out", type=Path, default=Path("gyrostat-results"),
                     help="output folder; each scene's results go to OUT/<scene>/ (default: %(default)s)")
    run.add_argument("--quiet", action="store_true", help="no progress bars")
    run.add_argument("--overwrite", action="store_true", help="replace the results of an earlier run in OUT")
    run.add_argument("--allow-import", action="append", metavar="MODULE", help=ALLOW_HELP)
    check = sub.add_parser("check", help="validate scene files without running them or any code they name",
                           description="Checks each scene as `gyrostat run` would (keys, values, models, tolerances, "
                                       "events), without solving it and without importing or calling any code it "
                                       "names (a user torque's function).")
    check.add_argument("scenes", nargs="+", type=Path, help="scene files (TOML)")
    check.add_argument("--allow-import", action="append", metavar="MODULE", help=ALLOW_HELP)
    examples = sub.add_parser("examples", help="run every example scene shipped with the package",
                              description="Runs every scene shipped with the package (gyrostat/scenes/*.toml) as "
                                          "gyrostat run does: results in OUT/<scene>/, a summary table at the end, "
                                          "OUT/index.html and OUT/index.md linking every scene's plots and report.",
                              epilog="example:\n  gyrostat examples --out results --overwrite   # then open "
                                     "results/index.html", formatter_class=argparse.RawDescriptionHelpFormatter)
    examples.add_argument("--out", type=Path, default=Path("gyrostat-results"), help="output folder (default: %(default)s)")
    examples.add_argument("--quiet", action="store_true", help="no progress bars")
    examples.add_argument("--overwrite", action="store_true", help="replace the results of an earlier run in OUT")
    sweep = sub.add_parser("sweep", help="solve a scene over a grid or a seeded dispersion of its entries",
                           description="Writes OUT/SCENE/sweep.nc (every member's summaries, and trajectories with "
                                       "--trajectories), sweep.png (the summary against the parameters) and "
                                       "sweep.json. Without --vary, the scene's [sweep] table says what to vary.")
    sweep.add_argument("scene", type=Path, help="a scene file (TOML)")
    sweep.add_argument("--vary", action="append", default=None, metavar="SPEC",
                       help="PATH=START:STOP:NUM[:log], PATH=V1,V2,..., or PATH~uniform(LOW,HIGH), "
                            "PATH~normal(MEAN,STD), PATH~loguniform(LOW,HIGH); e.g. 'body.moments[0]=1.0:2.0:11' "
                            "(repeat for a grid over several parameters)")
    sweep.add_argument("--samples", type=int, help="members of a dispersion")
    sweep.add_argument("--seed", type=int, help="seed of a dispersion (default: a fresh one, recorded)")
    sweep.add_argument("--run", help="the scene's run to sweep (default: its only run, or full)")
    sweep.add_argument("--summary", help="what the plot shows: a variable of sweep.nc or an expression such as "
                                         "'final_x / final_y'")
    sweep.add_argument("--trajectories", action="store_true", help="keep every member's trajectory in sweep.nc")
    sweep.add_argument("--threads", type=int, default=0, help="C++ threads per chunk (default: every core)")
    sweep.add_argument("--workers", type=int, help="worker processes on this machine, -1: one per core (default: one "
                       "per core for a large sweep, else this process alone)")
    sweep.add_argument("--chunk-size", type=int, help="members per ensemble call (default: about 64 MB of results)")
    sweep.add_argument("--dask", metavar="ADDRESS", help="run the chunks on this Dask scheduler (tcp://host:8786)")
    sweep.add_argument("--out", type=Path, default=Path("gyrostat-results"), help="output folder (default: %(default)s)")
    sweep.add_argument("--quiet", action="store_true", help="no progress bar")
    sweep.add_argument("--overwrite", action="store_true", help="replace an earlier sweep of the scene in OUT")
    sweep.add_argument("--allow-import", action="append", metavar="MODULE", help=ALLOW_HELP)
    sub.add_parser("methods", help="list the integrators, one line each")
    sub.add_parser("scene-format", help="print the reference of every scene kind (Markdown)")
    args = parser.parse_args(argv)

    if args.command == "methods":
        from gyrostat import _core

        names = _core.methods()
        width = max(map(len, names))
        print("\n".join(f"{name.ljust(width)}  {line}" for name, line in zip(names, _core.method_descriptions())))
        return 0
    if args.command == "scene-format":
        from gyrostat.scene import scene_format

        print(scene_format())
        return 0

    import warnings

    from gyrostat import output
    from gyrostat.runner import prepare_sweep, run_scene, run_sweep
    from gyrostat.scene import Scene
    from gyrostat.schema import SceneError
    from gyrostat.validity import ValidityWarning

    if args.command == "sweep":
        return _sweep(args)
    if args.command == "check":
        return _check(args)
    paths = args.scenes if args.command == "run" else example_scenes()
    allow_import = args.allow_import if args.command == "run" else None
    bad_scenes = failures = 0
    rows: list[tuple[str, ...]] = []
    for path in paths:
        try:
            scene = Scene.from_file(path, allow_import=allow_import)
            job = prepare_sweep(scene) if "sweep" in scene.doc else None  # its [sweep] checked before any run
        except KeyboardInterrupt:
            print(f"{path}: interrupted", file=sys.stderr)
            return 130
        except Exception as error:  # noqa: BLE001 - SceneError, a user factory's error: the scene is wrong, nothing ran
            print(f"{path}: error: {_one_line(error)}", file=sys.stderr)
            bad_scenes += 1
            continue
        try:
            output.claim_folder(args.out / Path(path).stem, args.overwrite)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)  # printed in the report below
                warnings.simplefilter("ignore", RuntimeWarning)   # an interrupted run: in its report
                report = run_scene(scene, args.out, progress=not args.quiet)
        except KeyboardInterrupt:
            print(f"{path}: interrupted", file=sys.stderr)
            return 130
        except SceneError as error:
            print(f"{path}: error: {error}", file=sys.stderr)
            bad_scenes += 1
            continue
        except output.FolderInUse as error:
            print(f"{path}: error: {error}", file=sys.stderr)
            failures += 1
            continue
        except Exception as error:  # noqa: BLE001 - the run failed (a user torque raised, ...): one line
            print(f"{path}: error: the run failed: {_one_line(error)}"
                  + (f" (the scene runs user code: {_code_names(scene)})" if scene.names_code else ""), file=sys.stderr)
            failures += 1
            continue
        _print_report(report)
        rows.append(_summary_row(report, args.out))
        failures += report["status"] != "success"
        if job is not None and report["status"] != "interrupted":  # the scene's [sweep] as well
            try:
                swept = run_sweep(job, args.out, progress=False if args.quiet else None)
                _print_sweep(swept)
                note = "WARNING members break assumptions" if swept.get("unexpected_broken") else "ok"
                rows[-1] = (*rows[-1][:2], f"{rows[-1][2]}; sweep of {swept['members']}: {note}", *rows[-1][3:])
            except KeyboardInterrupt:
                print(f"{path}: sweep interrupted", file=sys.stderr)
                return 130
            except Exception as error:  # noqa: BLE001 - one line, never a traceback
                print(f"{path}: sweep error: {_one_line(error)}", file=sys.stderr)
                failures += 1
        if report["status"] == "interrupted":
            print(f"{path}: interrupted; the outputs computed so far are written", file=sys.stderr)
            return 130
    if len(paths) > 1 and rows:
        _print_summary(rows)
    if rows:
        index, _ = write_index(args.out)
        print(f"index of every scene's plots and report: {index.resolve()}")
    if bad_scenes + failures < len(paths):
        print(f"results in {args.out.resolve()}")
    return 2 if bad_scenes else (1 if failures else 0)


if __name__ == "__main__":
    sys.exit(main())
