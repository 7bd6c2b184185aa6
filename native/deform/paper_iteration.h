// The paper's iteration (docs/design.md section 2): rotate every triangle's
// normal onto its label's axis (poisson_rhs.h), then solve L x = b, until the
// largest normal deviation is below the tolerance or the iteration limit is
// reached. The `fixed` variant assembles and factorises the input's
// Laplacian once (one back-substitution per iteration); `current`, as in the
// paper, the current mesh's every iteration (same pattern: the symbolic
// analysis of Deformation is reused).
//
// Inputs: a Deformation (deformation.h) just built, with variant kFixed or
// kCurrent. Outputs: its positions, figures and iteration count moved on.
#pragma once

#include "deform/deformation.h"

namespace polycube {

void paper_iteration(Deformation& deformation);

}  // namespace polycube
