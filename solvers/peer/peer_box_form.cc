// The box-MLCP → physics-engine box-LCP rewrite (peer_box_form.h).
#include "solvers/peer/peer_box_form.h"

#include <algorithm>
#include <cmath>

namespace smcbench {

void ToPeerBoxForm(const BoxMLCP& problem, PeerBoxForm* form) {
  const int n = problem.size();
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  const DenseMatrix& M = problem.dense_matrix();
  form->shift.resize(n);
  for (int i = 0; i < n; ++i) form->shift[i] = std::clamp(0.0, l[i], u[i]);
  form->permutation.clear();
  const auto is_free = [&](int i) { return std::isinf(l[i]) && l[i] < 0 && std::isinf(u[i]) && u[i] > 0; };
  for (int i = 0; i < n; ++i) {
    if (is_free(i)) form->permutation.push_back(i);
  }
  form->nub = static_cast<int>(form->permutation.size());
  for (int i = 0; i < n; ++i) {
    if (!is_free(i) && l[i] != u[i]) form->permutation.push_back(i);
  }
  const int m = static_cast<int>(form->permutation.size());
  form->A.resize(m, m);
  form->b.resize(m);
  form->lo.resize(m);
  form->hi.resize(m);
  for (int k = 0; k < m; ++k) {
    const int i = form->permutation[k];
    for (int c = 0; c < m; ++c) form->A(k, c) = M(i, form->permutation[c]);
    // b = −(q + M c) over every column (a fixed row's c = l is its whole contribution); c = 0 adds nothing, so
    // b = −q bitwise when nothing is shifted.
    double qc = problem.q()[i];
    for (int j = 0; j < n; ++j) {
      if (form->shift[j] != 0.0) qc += M(i, j) * form->shift[j];
    }
    form->b[k] = -qc;
    // l − c and u − c: ±inf stays ±inf, and c = 0 leaves the bound bitwise unchanged.
    form->lo[k] = l[i] - form->shift[i];
    form->hi[k] = u[i] - form->shift[i];
  }
}

PeerBoxForm ToPeerBoxForm(const BoxMLCP& problem) {
  PeerBoxForm form;
  ToPeerBoxForm(problem, &form);
  return form;
}

void ToPeerPoint(const PeerBoxForm& form, const Vector& z, Vector* x) {
  x->resize(form.size());
  for (int k = 0; k < form.size(); ++k) {
    const int i = form.permutation[k];
    (*x)[k] = z[i] - form.shift[i];
  }
}

void FromPeerPoint(const PeerBoxForm& form, const Vector& x, Vector* z) {
  *z = form.shift;
  for (int k = 0; k < form.size(); ++k) {
    const int i = form.permutation[k];
    (*z)[i] = form.shift[i] + x[k];
  }
}

}  // namespace smcbench
