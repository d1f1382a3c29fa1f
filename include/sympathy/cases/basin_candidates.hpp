// The attractors a basin run may be certified to end on, at one grid point: the stable periodic
// orbits reached from the case's starts (a transient inside each start's invariant subspace,
// then Newton: find_periodic_orbit), each named by the class the classifier gives its own motion
// ("anti-phase", "in-phase": the name a full-length run ending on it gets), each once.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/sync_classifier.hpp"
#include "sympathy/continuation/convergence_certificate.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

struct BasinCandidateStart {
  std::string name;  // the case's start
  Eigen::VectorXd state;
  InvariantSubspace subspace;
};

struct BasinCandidate {
  std::string start;  // the start it was reached from
  std::string name;   // the class of its own motion
  PeriodicOrbit orbit;
  std::shared_ptr<const OrbitNeighbourhood> neighbourhood;  // what its certificates need
  // The pendula's angles over one period from the orbit's point, at period / angles.size() steps:
  // a certified run's future, which the classifier is given in place of integrating it.
  std::vector<std::vector<double>> angles;
  // The angles at time s after the orbit's point (periodic; linear between the samples: 2000 a
  // period, error about (2 pi / 2000)^2 / 8 = 1.2e-6 of the amplitude).
  std::vector<double> angles_at(double s) const;
};

// Those of the orbits reached from `starts` on `model` (at its default parameters) that are
// stable with the certificate's margin, in the starts' order; an orbit reached from two starts
// (the same class and period to 1e-6) once. A start that reaches no orbit gives none.
std::vector<BasinCandidate> basin_candidates(const MetronomeModel& model,
                                             const std::vector<BasinCandidateStart>& starts,
                                             const OrbitOptions& orbit,
                                             const CertificateOptions& certificate,
                                             const std::vector<std::vector<int>>& groups,
                                             const SyncClassifierOptions& classifier, double dt);

}  // namespace sympathy
