#include <rbc_ifem/coupling/multilevel_membrane_term.h>

namespace rbc_ifem
{
  MultilevelMembraneTerm::MultilevelMembraneTerm(
    VelocityMultigrid           &levels,
    const MappingQ<3>           &level_mapping,
    const SemiImplicitLoad      &fine,
    const CellPopulation        &cells,
    const std::optional<double> &period,
    const double                &time_step)
    : levels(levels)
    , fine(fine)
    , cells(cells)
  {
    for (unsigned int level = 0; level + 1 < levels.n_levels(); ++level)
      {
        const DoFHandler<3> &dofs = levels.level_dof_handler(level);
        // Points are placed every step: with the support points cached, a
        // level's placing costs what the fine level's does.
        mappings.push_back(
          std::make_unique<MappingQCache<3>>(level_mapping.get_degree()));
        mappings.back()->initialize(level_mapping, dofs.get_triangulation());
        couplings.push_back(std::make_unique<ImmersedCoupling>(
          dofs.get_triangulation(), *mappings.back(), dofs, period));
        loads.push_back(std::make_unique<SemiImplicitLoad>(
          *couplings.back(),
          cells,
          levels.level_zero_constraints(level),
          time_step));
      }
  }

  bool
  MultilevelMembraneTerm::placed(const unsigned int level)
  {
    // A coarser mesh's quadratic cells follow the curved wall less closely
    // than the fine mesh's: a point the fine mesh holds, a hair from the
    // wall, may lie outside one. That level then goes without L this
    // step (every rank alike, as place() throws): the V-cycle is still a
    // preconditioner, only a weaker one.
    try
      {
        couplings[level]->place(cells.points());
        return true;
      }
    catch (const std::runtime_error &)
      {
        return false;
      }
  }

  void
  MultilevelMembraneTerm::update()
  {
    const unsigned int                       n = levels.n_levels();
    std::vector<VelocityOperator::AddedTerm> terms(n);
    std::vector<VelocityVector>              diagonals(n);
    // Once for all levels, in this rank's rows: each level's L sends them
    // to the ranks of its own mesh that hold the points.
    const std::vector<Tensor<1, 3>> stiffness_diagonal =
      cells.owned_stiffness_diagonal();
    for (unsigned int level = 0; level < n; ++level)
      {
        const bool fine_level = level + 1 == n;
        levels.initialize_level_vector(level, diagonals[level]);
        if (!fine_level && !placed(level))
          continue;
        const SemiImplicitLoad &L = fine_level ? fine : *loads[level];
        L.add_diagonal(stiffness_diagonal, diagonals[level]);
        terms[level] = [&L](const VelocityVector &v, VelocityVector &result) {
          L(v, result);
        };
      }
    levels.set_added_terms(terms, diagonals);
  }
} // namespace rbc_ifem
