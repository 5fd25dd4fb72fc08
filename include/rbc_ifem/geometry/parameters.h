#ifndef rbc_ifem_geometry_parameters_h
#define rbc_ifem_geometry_parameters_h

#include <rbc_ifem/base/parameter_tools.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <optional>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The parameters of the geometry: the capillary segment, its meshes, the
   * cells' reference shape and their layout. Each struct's initializers are
   * the defaults; add_parameters() declares its subsection with them and
   * binds the members, so parsing a file fills them (doc/design.md,
   * "Parameters"). Units: µm.
   */

  /// The capillary segment and the tissue around it (subsection "Geometry").
  struct GeometryParameters
  {
    double capillary_radius    = 5.0;  ///< lumen radius [µm]
    double capillary_length    = 20.0; ///< segment length along x [µm]
    double wall_thickness      = 1.0;  ///< vessel wall [µm]
    double gas_layer_thickness = 5.0;  ///< alveolar gas layer [µm]
    /// The segment repeats along x: what leaves at x = L enters at x = 0.
    bool periodic = false;

    /// The period along x, Capillary length, if Periodic; none otherwise.
    std::optional<double>
    period() const;

    void
    add_parameters(ParameterHandler &prm);
  };

  /// Refinement of the two volume meshes (subsection "Mesh").
  struct MeshParameters
  {
    unsigned int fluid_global_refinements     = 1;
    unsigned int fluid_band_refinements       = 1;
    unsigned int diffusion_global_refinements = 1;
    unsigned int diffusion_band_refinements   = 1;
    double       band_width                   = 0.5; ///< [µm]
    /// Diffusion/Method = cut cell: refinements where two membranes share
    /// a cell of the diffusion mesh.
    unsigned int diffusion_gap_refinements = 3;

    void
    add_parameters(ParameterHandler &prm);
  };

  /// The reference shape of the cells (Cells/Shape).
  enum class ReferenceShape
  {
    biconcave, ///< the Evans-Fung red cell
    sphere     ///< a spherical capsule, the validation runs
  };

  const SelectionNames<ReferenceShape> &
  reference_shape_names();

  /// The red cells' reference shape and its surface mesh (subsection "Cells").
  struct CellParameters
  {
    ReferenceShape shape               = ReferenceShape::biconcave;
    double         diameter            = 7.5; ///< Evans-Fung diameter 2R [µm]
    unsigned int   surface_refinements = 3;
    Tensor<1, 3>   axis{{1., 0., 0.}}; ///< symmetry axis, unit length

    void
    add_parameters(ParameterHandler &prm);
    /// Throws InputError unless the axis is a direction.
    void
    validate() const;
  };

  /// How the cells are placed along the segment (Layout/Kind).
  enum class LayoutKind
  {
    uniform,
    random,
    clustered,
    file ///< centres and axes read from Layout/File
  };

  const SelectionNames<LayoutKind> &
  layout_kind_names();

  /// Where the cells sit in the segment (subsection "Layout").
  struct LayoutParameters
  {
    LayoutKind   kind             = LayoutKind::uniform;
    unsigned int n_cells          = 4;
    unsigned int seed             = 1;
    double       minimum_gap      = 0.2; ///< [µm]
    double       cluster_position = 0.5; ///< centre of a cluster / length
    /// Kind = file: the CSV file x,y,z,axis_x,axis_y,axis_z, a row per cell.
    std::string file;

    void
    add_parameters(ParameterHandler &prm);
    /// Throws InputError unless Minimum gap > 0 and Kind = file has a File.
    void
    validate() const;
  };

  /**
   * The layouts of the paper's study (subsection "Layout study"), for the
   * experiments 'layouts' (rigid cells) and 'flowing layouts' (cells
   * carried by the plasma): every Kind for every number of cells, several
   * seeds for random layouts; the other entries come from subsection
   * Layout.
   */
  struct LayoutStudyParameters
  {
    std::vector<LayoutKind>   kinds{LayoutKind::uniform,
                                  LayoutKind::random,
                                  LayoutKind::clustered};
    std::vector<unsigned int> numbers_of_cells{1, 2, 3, 4, 5, 6, 7};
    unsigned int              n_seeds = 5;

    void
    add_parameters(ParameterHandler &prm);
    /// Throws InputError if Kinds holds file: a file is one layout.
    void
    validate() const;

    /**
     * The layouts of the study, in order: for each kind, for each number of
     * cells, its samples (seeds @p layout.seed, @p layout.seed + 1, ... for
     * random layouts, one otherwise), every other entry from @p layout.
     */
    std::vector<std::vector<LayoutParameters>>
    layouts(const LayoutParameters &layout) const;
  };
} // namespace rbc_ifem

#endif
