"""Exceptions that the CLI turns into exit codes.

``InputError``      bad scene input  -> one line on stderr, exit code 2.
``ConvergenceError`` a solver did not reach its tolerance -> the model is reported ``failed``.
"""


class InputError(ValueError):
    """A scene key has a bad value. ``str(err)`` is the one line shown to the user."""

    def __init__(self, key: str, message: str):
        self.key = key
        super().__init__(f"{key}: {message}")


class ConvergenceError(RuntimeError):
    """An iterative solver stopped without meeting its tolerance.

    Carries the iteration count and the last residual so the failure is reported with numbers.
    """

    def __init__(self, solver: str, iterations: int, residual: float, tolerance: float, detail: str = ""):
        self.solver = solver
        self.iterations = iterations
        self.residual = residual
        self.tolerance = tolerance
        msg = (f"{solver} did not converge: residual {residual:.3e} > tolerance {tolerance:.1e} "
               f"after {iterations} iterations")
        super().__init__(msg + (f" ({detail})" if detail else ""))
