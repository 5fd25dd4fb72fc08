#include <rbc_ifem/ifem/run_record.h>

namespace rbc_ifem
{
  RunRecord::RunRecord(const unsigned int n_cells, const bool reaction)
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
