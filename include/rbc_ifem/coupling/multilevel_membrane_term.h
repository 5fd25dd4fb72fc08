#ifndef rbc_ifem_coupling_multilevel_membrane_term_h
#define rbc_ifem_coupling_multilevel_membrane_term_h

#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/immersed_coupling.h>
#include <rbc_ifem/coupling/semi_implicit_load.h>
#include <rbc_ifem/fluid/velocity_multigrid.h>

#include <deal.II/fe/mapping_q.h>
#include <deal.II/fe/mapping_q_cache.h>

#include <memory>
#include <optional>
#include <vector>

namespace rbc_ifem
{
  /**
   * The semi-implicit coupling's membrane term L = Δt Sᵀ K S on every level
   * of the velocity multigrid (doc/ifem.md, "The preconditioner of the
   * semi-implicit step"), so that its V-cycle approximates (A + L)⁻¹, not
   * A⁻¹. Each coarser level places the membrane points on its own mesh
   * (an ImmersedCoupling there) and applies its own L, as the fine level
   * does; since the coarser velocity spaces are nested in the fine one and
   * interpolation at the points is exact for them, the level's L is the
   * fine L restricted to it. The smoothers take the diagonal of A + L, L's
   * estimated by SemiImplicitLoad::add_diagonal(). The coarsest level's
   * solve keeps A alone: solving A + L there exactly (with an LU, as the
   * coarse solve then was) saved a tenth of the outer iterations at twice
   * the time.
   */
  class MultilevelMembraneTerm
  {
  public:
    /**
     * For the levels of @p levels below the fine one, whose mapping is
     * @p level_mapping; @p fine is the fine level's L. The cells, the
     * period and @p time_step are those of @p fine, read at every use.
     */
    MultilevelMembraneTerm(VelocityMultigrid           &levels,
                           const MappingQ<3>           &level_mapping,
                           const SemiImplicitLoad      &fine,
                           const CellPopulation        &cells,
                           const std::optional<double> &period,
                           const double                &time_step);

    /**
     * Place the membrane points on every coarser level and give every
     * level its L, at the stiffness of the cells' last
     * CellPopulation::linearize(): once a step, after it.
     */
    void
    update();

  private:
    /// Place the points on coarser level @p level; false if one lies
    /// outside its mesh.
    bool
    placed(unsigned int level);

    VelocityMultigrid      &levels;
    const SemiImplicitLoad &fine;
    const CellPopulation   &cells;
    /// Per coarser level, coarsest first: its mapping's support points,
    /// the points placed on it, and its L.
    std::vector<std::unique_ptr<MappingQCache<3>>> mappings;
    std::vector<std::unique_ptr<ImmersedCoupling>> couplings;
    std::vector<std::unique_ptr<SemiImplicitLoad>> loads;
  };
} // namespace rbc_ifem

#endif
