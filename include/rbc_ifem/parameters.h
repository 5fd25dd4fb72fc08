#ifndef rbc_ifem_parameters_h
#define rbc_ifem_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

/**
 * Everything rbc-ifem reads from a .prm file. Units (design.md, Section 3):
 * length µm, time s, force pN. The names of the parameters listed in
 * design.md, Section 6 are part of the public interface and never change.
 */
namespace rbc_ifem
{
  using namespace dealii;

  /// The capillary segment and the tissue around it (subsection "Geometry").
  struct GeometryParameters
  {
    double capillary_radius    = 5.0;  ///< lumen radius [µm]
    double capillary_length    = 20.0; ///< segment length along x [µm]
    double wall_thickness      = 1.0;  ///< vessel wall [µm]
    double gas_layer_thickness = 5.0;  ///< alveolar gas layer [µm]

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
    /// Throws InputError unless every length is positive.
    void
    validate() const;
  };

  /// Refinement of the two volume meshes (subsection "Mesh").
  struct MeshParameters
  {
    unsigned int fluid_global_refinements     = 1;
    unsigned int fluid_band_refinements       = 1;
    unsigned int diffusion_global_refinements = 1;
    unsigned int diffusion_band_refinements   = 3;
    double       band_width                   = 0.5; ///< [µm]

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /// The red cells' reference shape and its surface mesh (subsection "Cells").
  struct CellParameters
  {
    std::string  shape               = "biconcave"; ///< biconcave | sphere
    double       diameter            = 7.5; ///< Evans-Fung diameter 2R [µm]
    unsigned int surface_refinements = 3;
    Tensor<1, 3> axis{{1., 0., 0.}}; ///< symmetry axis, unit length

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
    /// Throws InputError unless the cell fits into the capillary's diameter.
    void
    validate(const GeometryParameters &geometry) const;
  };

  /// Where the cells sit in the segment (subsection "Layout").
  struct LayoutParameters
  {
    std::string  kind             = "uniform"; ///< uniform | random | clustered
    unsigned int n_cells          = 4;
    unsigned int seed             = 1;
    double       minimum_gap      = 0.2; ///< [µm]
    double       cluster_position = 0.5; ///< centre of a cluster / length

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /// The plasma and how its flow is solved (subsection "Fluid").
  struct FluidParameters
  {
    std::string  model                 = "Stokes"; ///< Stokes | Navier-Stokes
    double       viscosity             = 1.2e-3;   ///< μ [pN s/µm²]
    double       density               = 1e-9;     ///< ρ [mg/µm³]
    double       inlet_mean_speed      = 500.;     ///< ū [µm/s]
    double       frame_velocity        = 0.;       ///< U_frame along x [µm/s]
    double       linear_tolerance      = 1e-6;     ///< relative, FGMRES
    unsigned int max_linear_iterations = 500;
    double       newton_tolerance = 1e-8; ///< relative to the first residual
    unsigned int max_newton_iterations = 20;

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /// Time stepping (subsection "Time").
  struct TimeParameters
  {
    double       time_step       = 1e-3; ///< Δt [s]
    unsigned int n_steps         = 10;
    unsigned int output_interval = 1; ///< VTU every this many steps

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /**
   * The red cell membrane's mechanics (subsection "Membrane"): energies and
   * moduli in pN and µm. See Membrane and doc/membrane.md.
   */
  struct MembraneParameters
  {
    std::string  law           = "neo-Hookean"; ///< neo-Hookean | Skalak
    double       shear_modulus = 5.5;           ///< G_s [pN/µm]
    double       area_dilation_modulus = 500.;  ///< K [pN/µm]
    double       bending_modulus       = 0.2;   ///< κ [pN µm]
    double       spontaneous_curvature = 0.;    ///< c0 [1/µm]
    double       area_penalty          = 500.;  ///< k_A [pN/µm]
    double       volume_penalty        = 500.;  ///< k_V [pN/µm²]
    unsigned int degree                = 1;     ///< of FE_Q<2,3>

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /**
   * Experiment "flow" with red cells in the plasma, the immersed method
   * (subsection "Immersed cells"): what the time loop of IFEMSimulation
   * does besides the steps of subsection Time.
   */
  struct ImmersedParameters
  {
    bool enabled      = false; ///< carry the cells of subsection Layout
    bool follow_cells = true;  ///< frame velocity = the cells' mean velocity
    unsigned int diffusion_interval = 0; ///< DM every this many steps; 0: never
    unsigned int checkpoint_interval = 0; ///< 0: never
    bool         resume = false; ///< from Output directory/checkpoint.bin
    double max_step_displacement = 0.25; ///< of the fluid mesh size h, per step
    unsigned int progress_interval =
      10;                         ///< a progress line every this many steps
    double tether_stiffness = 0.; ///< springs to the start [pN/µm]; 0: free

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /// The optical-tweezers experiment (subsection "Stretching").
  struct StretchingParameters
  {
    double       max_force         = 200.; ///< [pN]
    unsigned int n_force_steps     = 8;
    double       attached_fraction = 0.025; ///< of the membrane area, per bead
    double       tolerance         = 1e-3;  ///< nodal force residual [pN]
    unsigned int max_iterations    = 20000;

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /**
   * Experiment "shear" (subsection "Shear"): one spherical capsule in the
   * middle of a box in simple shear v = (γ̇ y, 0, 0), run once for every
   * capillary number Ca = μ a γ̇ / G (a = Cells/Diameter / 2).
   */
  struct ShearParameters
  {
    double              shear_rate = 100.; ///< γ̇ [1/s]
    std::vector<double> capillary_numbers{0.0125, 0.025, 0.05, 0.1, 0.2};
    Tensor<1, 3>        box{
      {24., 24., 24.}}; ///< length (x), height (y), width (z) [µm]
    double strain = 4.;        ///< run length γ̇ t
    double averaging_strain =
      0.5; ///< steady values: means over the steadiest window of this γ̇ t
    double output_strain      = 0.25; ///< VTU and shear.csv every γ̇ t
    double time_step_fraction = 0.5;  ///< of the explicit-coupling limit

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
    /// Throws InputError unless the capsule fits and the strains make sense.
    void
    validate(const CellParameters &cells) const;
  };

  /**
   * Steady CO diffusion (subsection "Diffusion"): ∇·(αD∇P) = 0 with αD
   * piecewise constant per material, P = P_A on the alveolar surface and
   * P = 0 on every membrane (imposed by a Lagrange multiplier, see
   * CODiffusion). Defaults from the paper's Table 2.
   */
  struct DiffusionParameters
  {
    double       alveolar_pressure     = 1.;       ///< P_A [Torr]
    double       plasma_diffusivity    = 2.453e3;  ///< D [µm²/s]
    double       plasma_solubility     = 2.363e-5; ///< α [Torr⁻¹]
    double       wall_diffusivity      = 2.453e3;  ///< D [µm²/s]
    double       wall_solubility       = 2.363e-5; ///< α [Torr⁻¹]
    double       gas_diffusivity       = 2.413e7;  ///< D [µm²/s]
    double       gas_solubility        = 1.159e-3; ///< α [Torr⁻¹]
    unsigned int degree                = 1;        ///< of FE_Q<3> for P
    double       augmentation          = 30.;      ///< γ, dimensionless
    double       linear_tolerance      = 1e-8;     ///< relative, FGMRES
    unsigned int max_linear_iterations = 1000;

    /// αD of the material with this id (Material::plasma, ...) [µm²/(s Torr)].
    double
    permeability(const unsigned int material_id) const;

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /**
   * The paper's layout experiment (subsection "Layout study"): every Kind
   * for every number of cells, several seeds for random layouts.
   */
  struct LayoutStudyParameters
  {
    std::vector<std::string>  kinds{"uniform", "random", "clustered"};
    std::vector<unsigned int> numbers_of_cells{1, 2, 3, 4, 5, 6, 7};
    unsigned int              n_seeds = 5;

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /// The mesh-convergence experiment (subsection "Mesh convergence").
  struct MeshConvergenceParameters
  {
    unsigned int n_levels = 4;

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /// All parameters of one run.
  struct Parameters
  {
    std::string               experiment       = "geometry";
    std::string               output_directory = "output/run";
    GeometryParameters        geometry;
    MeshParameters            mesh;
    CellParameters            cells;
    LayoutParameters          layout;
    FluidParameters           fluid;
    TimeParameters            time;
    MembraneParameters        membrane;
    ImmersedParameters        immersed;
    StretchingParameters      stretching;
    ShearParameters           shear;
    DiffusionParameters       diffusion;
    LayoutStudyParameters     layout_study;
    MeshConvergenceParameters mesh_convergence;

    /// Declare every parameter, with its pattern and documentation.
    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm);
  };

  /**
   * Read @p filename into @p prm and @p parameters, and check what can be
   * checked without building anything. Throws InputError, naming the file,
   * the parameter and the value, if the file cannot be read, holds an
   * unknown entry or a value outside its pattern, or asks for something
   * physically impossible.
   */
  void
  read_parameters(const std::string &filename,
                  ParameterHandler  &prm,
                  Parameters        &parameters);
} // namespace rbc_ifem

#endif
