"""The command line: ``gyrostat run SCENE.toml``, ``gyrostat examples``, ``gyrostat methods``."""

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
        drift = ", ".join(f"{k} {v:+.3e}" for k, v in run["invariant_relative_change"].items())
        print(f"  {name}: {run['method']}, {run['status']}; steps {stats['steps']}, rhs evaluations "
              f"{stats['rhs_evals']}, rejected {stats['rejected_steps']}; relative change: {drift}")
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
    parser = argparse.ArgumentParser(prog="gyrostat", description="Perturbed rotation of rigid bodies and gyrostats.")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="solve one or more scene files, save results and plots")
    run.add_argument("scenes", nargs="+", type=Path, help="scene files (TOML)")
    run.add_argument("--out", type=Path, default=Path("gyrostat-results"), help="output folder (default: %(default)s)")
    run.add_argument("--quiet", action="store_true", help="no progress lines")
    examples = sub.add_parser("examples", help="run every example scene shipped with the package")
    examples.add_argument("--out", type=Path, default=Path("gyrostat-results"), help="output folder (default: %(default)s)")
    examples.add_argument("--quiet", action="store_true", help="no progress lines")
    sub.add_parser("methods", help="list the integrators")
    args = parser.parse_args(argv)

    if args.command == "methods":
        from gyrostat import METHODS

        print("\n".join(METHODS))
        return 0

    import warnings

    from gyrostat.runner import run_scene
    from gyrostat.validity import ValidityWarning

    paths = args.scenes if args.command == "run" else example_scenes()
    failures = 0
    for path in paths:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)  # printed in the report below
                report = run_scene(path, args.out, progress=not args.quiet)
        except (ValueError, OSError) as error:
            print(f"{path}: error: {error}", file=sys.stderr)
            failures += 1
            continue
        _print_report(report)
        failures += report["status"] != "success"
    print(f"results in {args.out.resolve()}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
