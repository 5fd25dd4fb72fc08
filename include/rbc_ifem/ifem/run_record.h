#ifndef rbc_ifem_ifem_run_record_h
#define rbc_ifem_ifem_run_record_h

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/diffusion/uptake.h>

#include <string>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  /**
   * What a flowing run has produced so far and where it stands: its tables,
   * the records of its .pvd files, the step, the time and how far the frame
   * has moved. The tables are rewritten whole from it, so a run that stops
   * leaves complete files, and a checkpoint carries it.
   */
  struct RunRecord
  {
    /// An empty record (what a checkpoint is read into).
    RunRecord() = default;

    /// The record of a run of @p n_cells cells from its start: the tables'
    /// headers (dm.csv's with DL columns if @p reaction), no rows.
    RunRecord(const unsigned int n_cells, const bool reaction);

    unsigned int step     = 0;
    double       time     = 0.; ///< [s]
    double   frame_offset = 0.; ///< distance the frame has moved along x [µm]
    CsvTable flow, cells, dm;   ///< flow.csv, cells.csv, dm.csv
    std::vector<std::pair<double, std::string>> fluid_files;
    std::vector<std::vector<std::pair<double, std::string>>>
                 cell_files;    ///< per cell
    UptakeFields uptake_fields; ///< diffusion.pvd, diffusion_membranes.pvd
    /// Every DM solve so far: (time [s], DM [µm³ s⁻¹ Torr⁻¹]).
    std::vector<std::pair<double, double>> dm_history;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &step &time &frame_offset &flow &cells &dm &fluid_files
        &cell_files &uptake_fields &dm_history;
    }
  };

  // The constructor, inline: it names the tables' columns.
  inline RunRecord::RunRecord(const unsigned int n_cells, const bool reaction)
    : flow("time,flow_rate,pressure_drop,max_velocity,divergence_l2,"
           "frame_velocity,newton_iterations,linear_iterations,held_force_x,"
           "held_force_y,held_force_z,lab_flow_rate")
    , cells("time,cell,x,y,z,area,volume,axial_length,max_radius,"
            "deformation_index,frame_x,volume_change,area_change,"
            "taylor_deformation,inclination,min_gap,wall_gap,"
            "local_area_change")
    , dm(dm_header(n_cells, reaction))
    , cell_files(n_cells)
  {}
} // namespace rbc_ifem

#endif
