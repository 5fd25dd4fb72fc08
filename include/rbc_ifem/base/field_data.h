#ifndef rbc_ifem_base_field_data_h
#define rbc_ifem_base_field_data_h

#include <string>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  /**
   * VTK field data: (name, value) pairs a VTU file carries beside its
   * fields, one number each, which ParaView shows in its Information panel
   * and its Python reads as FieldData: for the files of a flowing run TIME
   * [s], FRAME_VELOCITY [µm/s] and FRAME_OFFSET [µm] (doc/outputs.md).
   */
  using FieldData = std::vector<std::pair<std::string, double>>;

  /// The field data of the files of a flowing run at @p time, whose frame
  /// moves at @p frame_velocity and has moved by @p frame_offset.
  FieldData
  frame_field_data(const double time,
                   const double frame_velocity,
                   const double frame_offset);
} // namespace rbc_ifem

#endif
