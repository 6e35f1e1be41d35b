"""Studies built from the solvers: coating studies, the cam-cycle study, sweeps."""
