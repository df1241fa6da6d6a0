#!/bin/bash
# A stand-in for the conefeti program that ends every scene as "no equilibrium" (exit 2, the JSON line of a run
# that did not converge): scripts/fuzz-scenes.py must count it as a wrong result on a scene with a unique solution.
echo "NOT CONVERGED: no equilibrium: the equality (rigid-body equilibrium) cannot be met with admissible contact forces"
echo '{"conefeti":"stand-in","converged":false,"reason":"no equilibrium","residuals":{"max":1.0}}'
exit 2
