"""The command line: ``gyrostat run SCENE.toml``, ``gyrostat examples``, ``gyrostat methods``,
``gyrostat scene-format``; ``gyrostat --version``. Also ``python -m gyrostat``.

Exit codes: 0 every scene ran and succeeded; 1 a run failed (its partial results are written);
2 a scene file is wrong (a one-line message names the key and the table, no traceback)."""

from __future__ import annotations

import argparse
import sys
from importlib import resources
from pathlib import Path


def example_scenes() -> list[Path]:
    """The scenes shipped with the package."""
    folder = resources.files("gyrostat") / "scenes"
    return sorted(Path(str(p)) for p in folder.iterdir() if p.name.endswith(".toml"))


def _print_report(report: dict) -> None:
    print(f"{report['scene']}: {report['title']}")
    print(f"  model: {report['model']} ({report['model_reason']}); status: {report['status']}; "
          f"time: {report['seconds']:.3g} s")
    for name, run in report.get("runs", {}).items():
        stats = run["stats"]
        drift = ", ".join(f"{k} {v['relative_change']:+.3e}" if "relative_change" in v else
                          f"{k} {v['max_abs_change']:.3e} (absolute)" for k, v in run["conserved"].items()
                          if v.get("relative_change", v.get("max_abs_change")) is not None)
        print(f"  {name}: {run['method']}, {run['status']}; steps {stats['steps']}, rhs evaluations "
              f"{stats['rhs_evals']}, rejected {stats['rejected_steps']}" + (f"; change of {drift}" if drift else ""))
        for event, times in run.get("events", {}).items():
            shown = ", ".join(f"{t:.6g}" for t in times[:5]) + (", ..." if len(times) > 5 else "")
            print(f"    event {event}: {len(times)} crossing(s)" + (f" at t = {shown}" if times else ""))
        if run["message"]:
            print(f"    message: {run['message']}")
    for key, diff in report.items():  # averaged_vs_full and its variants: name → max difference
        if key.startswith("averaged_vs_full") and isinstance(diff, dict):
            text = ", ".join(f"{name} {value:.3e}" for name, value in diff.items() if isinstance(value, float))
            print(f"  averaged vs full: {text}")
    for broken in report.get("broken_assumptions", []):
        print(f"  WARNING assumption broken: {broken}")
    if "max_error_vs_closed_form" in report:
        print(f"  max |omega - closed form| = {report['max_error_vs_closed_form']:.3e}")
    for f in report.get("files", []):
        print(f"  wrote {f}")


def main(argv: list[str] | None = None) -> int:
    from gyrostat import __version__

    parser = argparse.ArgumentParser(prog="gyrostat", description="Perturbed rotation of rigid bodies and gyrostats.")
    parser.add_argument("--version", action="version", version=f"gyrostat {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="solve one or more scene files, save results and plots")
    run.add_argument("scenes", nargs="+", type=Path, help="scene files (TOML)")
    run.add_argument("--out", type=Path, default=Path("gyrostat-results"), help="output folder (default: %(default)s)")
    run.add_argument("--quiet", action="store_true", help="no progress lines")
    examples = sub.add_parser("examples", help="run every example scene shipped with the package")
    examples.add_argument("--out", type=Path, default=Path("gyrostat-results"), help="output folder (default: %(default)s)")
    examples.add_argument("--quiet", action="store_true", help="no progress lines")
    sub.add_parser("methods", help="list the integrators")
    sub.add_parser("scene-format", help="print the reference of every scene kind (Markdown)")
    args = parser.parse_args(argv)

    if args.command == "methods":
        from gyrostat import METHODS

        print("\n".join(METHODS))
        return 0
    if args.command == "scene-format":
        from gyrostat.scene import scene_format

        print(scene_format())
        return 0

    import warnings

    from gyrostat.runner import run_scene
    from gyrostat.schema import SceneError
    from gyrostat.validity import ValidityWarning

    paths = args.scenes if args.command == "run" else example_scenes()
    bad_scenes = failures = 0
    for path in paths:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)  # printed in the report below
                warnings.simplefilter("ignore", RuntimeWarning)   # an interrupted run: in its report
                report = run_scene(path, args.out, progress=not args.quiet)
        except KeyboardInterrupt:
            print(f"{path}: interrupted", file=sys.stderr)
            return 130
        except SceneError as error:
            print(f"{path}: error: {error}", file=sys.stderr)
            bad_scenes += 1
            continue
        except (ValueError, OSError) as error:
            print(f"{path}: error: {' '.join(str(error).split())}", file=sys.stderr)
            failures += 1
            continue
        _print_report(report)
        failures += report["status"] != "success"
        if report["status"] == "interrupted":
            print(f"{path}: interrupted; the outputs computed so far are written", file=sys.stderr)
            return 130
    if bad_scenes + failures < len(paths):
        print(f"results in {args.out.resolve()}")
    return 2 if bad_scenes else (1 if failures else 0)


if __name__ == "__main__":
    sys.exit(main())
