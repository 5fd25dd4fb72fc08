#ifndef rbc_ifem_diffusion_uptake_h
#define rbc_ifem_diffusion_uptake_h

#include <rbc_ifem/base/field_data.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <string>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  class DiffusionSolver;

  /// What one CO uptake solve gives (UptakeSolver).
  struct Uptake
  {
    double              dm_total = 0.; ///< [µm³ s⁻¹ Torr⁻¹]
    std::vector<double> dm_cells;      ///< [µm³ s⁻¹ Torr⁻¹]
    /// With Diffusion/Uptake = reaction: DL, the CO bound inside the cells
    /// per Torr of P_A [µm³ s⁻¹ Torr⁻¹]; empty dl_cells otherwise.
    double              dl_total = 0.;
    std::vector<double> dl_cells;
    unsigned int        dl_iterations = 0; ///< of the reaction's solve
    unsigned int n_nodes = 0; ///< vertices of the volume mesh (all ranks')
    unsigned int n_cells = 0; ///< cells of the volume mesh (all ranks')
    /// Cells of the volume mesh that the rank holding the most holds (its
    /// own, their ghost layer and what they need of the coarser levels;
    /// every cell on a shared mesh).
    unsigned int            n_cells_largest_rank = 0;
    types::global_dof_index n_dofs               = 0; ///< P and λ
    unsigned int            iterations           = 0;
    double                  seconds = 0.; ///< wall time of the whole solve
  };

  /// The header of dm.csv for @p n_cells cells: time,dm_total,dm_cell_0,...
  /// and, with @p reaction, dl_total,dl_cell_0,...
  std::string
  dm_header(const unsigned int n_cells, const bool reaction);

  /// The dm.csv row of @p uptake at @p time [s].
  std::string
  dm_row(const double time, const Uptake &uptake);

  /**
   * The fields of a run's uptake solves, for ParaView: the CO partial
   * pressure of each solve (diffusion.pvd) and the membranes' flux map
   * (diffusion_membranes.pvd), one record per solve.
   */
  class UptakeFields
  {
  public:
    /// The fields written as NAME_*.pvtu (or .vtu) under NAME.pvd, the
    /// membranes under NAME_membranes.pvd.
    explicit UptakeFields(const std::string &name = "diffusion");

    /**
     * Write the fields of @p diffusion, solved at @p time [s], as the
     * @p counter-th into @p directory, each file carrying @p field_data,
     * and rewrite the two .pvd records.
     */
    void
    write(const DiffusionSolver &diffusion,
          const std::string     &directory,
          const double           time,
          const unsigned int     counter,
          const MPI_Comm         communicator,
          const FieldData       &field_data = {});

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &pressure &membranes;
    }

  private:
    std::string                                 name;
    std::vector<std::pair<double, std::string>> pressure, membranes;
  };
} // namespace rbc_ifem

#endif
