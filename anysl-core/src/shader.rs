//! Shader traits and parameter metadata (name, type, default, uniform/varying, output), with
//! setting parameters by name — the same for shaders written in Rust and loaded from `.sl`.

use crate::context::ShadingContext;
use crate::exec::Exec;
use crate::float::ShadingFloat;
use crate::globals::SurfaceOutput;
use crate::light::{Emission, LightCode, LightData, LightOutput, LightSource};
use crate::spaces::Spaces;
use crate::vec::{Color, Vec3};
use core::fmt;

/// The kind of a shader (RenderMan Interface 3.2 shader types).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShaderKind {
    /// Computes Ci/Oi at a surface point.
    Surface,
    /// Computes Cl/L for a light source.
    Light,
    /// Moves P / changes N before shading.
    Displacement,
    /// Attenuates along a ray.
    Volume,
    /// Post-processes pixels.
    Imager,
}

impl ShaderKind {
    /// The RSL keyword.
    #[must_use]
    pub fn keyword(self) -> &'static str {
        match self {
            Self::Surface => "surface",
            Self::Light => "light",
            Self::Displacement => "displacement",
            Self::Volume => "volume",
            Self::Imager => "imager",
        }
    }
}

/// The RSL type of a parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ParamType {
    /// `float`.
    Float,
    /// `color`.
    Color,
    /// `point`.
    Point,
    /// `vector`.
    Vector,
    /// `normal`.
    Normal,
    /// `string`.
    String,
    /// `matrix`.
    Matrix,
}

impl ParamType {
    /// The RSL keyword.
    #[must_use]
    pub fn keyword(self) -> &'static str {
        match self {
            Self::Float => "float",
            Self::Color => "color",
            Self::Point => "point",
            Self::Vector => "vector",
            Self::Normal => "normal",
            Self::String => "string",
            Self::Matrix => "matrix",
        }
    }
    /// True for color/point/vector/normal.
    #[must_use]
    pub fn is_triple(self) -> bool {
        matches!(self, Self::Color | Self::Point | Self::Vector | Self::Normal)
    }
}

/// `uniform` (one value for all shading points) or `varying` (one per point).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Storage {
    /// Same value for every shading point of a shader instance.
    Uniform,
    /// May differ per shading point.
    Varying,
}

/// A parameter value.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    /// A float.
    Float(f64),
    /// A color, point, vector or normal.
    Triple([f64; 3]),
    /// A string.
    String(String),
    /// A matrix in row order.
    Matrix([f64; 16]),
    /// A fixed-length array.
    Array(Vec<ParamValue>),
}

impl fmt::Display for ParamValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Float(v) => write!(f, "{v}"),
            Self::Triple([a, b, c]) => write!(f, "({a}, {b}, {c})"),
            Self::String(s) => write!(f, "{s:?}"),
            Self::Matrix(m) => {
                write!(f, "matrix(")?;
                for (i, v) in m.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{v}")?;
                }
                write!(f, ")")
            }
            Self::Array(items) => {
                write!(f, "{{")?;
                for (i, v) in items.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{v}")?;
                }
                write!(f, "}}")
            }
        }
    }
}

impl ParamValue {
    /// Parses a value of type `ty` from command-line text: `0.3`, `1,0.5,0.2`, `[1 0.5 0.2]`,
    /// a string as is, or 16 numbers for a matrix. A single number is promoted to a triple
    /// (as RSL promotes float to color). The error names what was expected.
    pub fn parse(ty: ParamType, text: &str) -> Result<Self, String> {
        if ty == ParamType::String {
            return Ok(Self::String(text.trim_matches('"').to_string()));
        }
        let cleaned: String =
            text.chars().map(|c| if matches!(c, '[' | ']' | '(' | ')' | ',') { ' ' } else { c }).collect();
        let nums: Result<Vec<f64>, _> = cleaned.split_whitespace().map(str::parse::<f64>).collect();
        let nums = nums.map_err(|_| format!("expected a {} value, got {text:?}", ty.keyword()))?;
        match (ty, nums.len()) {
            (ParamType::Float, 1) => Ok(Self::Float(nums[0])),
            (t, 1) if t.is_triple() => Ok(Self::Triple([nums[0]; 3])),
            (t, 3) if t.is_triple() => Ok(Self::Triple([nums[0], nums[1], nums[2]])),
            (ParamType::Matrix, 1) => {
                let mut m = [0.0; 16];
                for i in 0..4 {
                    m[i * 5] = nums[0];
                }
                Ok(Self::Matrix(m))
            }
            (ParamType::Matrix, 16) => Ok(Self::Matrix(nums.try_into().expect("16 numbers"))),
            (t, n) => Err(format!(
                "expected {} for a {} parameter, got {n} number(s) in {text:?}",
                match t {
                    ParamType::Float => "1 number",
                    ParamType::Matrix => "1 or 16 numbers",
                    _ => "1 or 3 numbers",
                },
                t.keyword()
            )),
        }
    }
}

/// Metadata of one parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamInfo {
    /// Name as written in the shader.
    pub name: String,
    /// RSL type.
    pub ty: ParamType,
    /// Array length, if the parameter is an array.
    pub array_len: Option<usize>,
    /// Default value (evaluated to a constant).
    pub default: ParamValue,
    /// `uniform` or `varying`.
    pub storage: Storage,
    /// True for `output` parameters (written by the shader).
    pub output: bool,
}

/// Metadata of a shader: what `sloinfo` prints.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderMeta {
    /// Shader name.
    pub name: String,
    /// Shader kind.
    pub kind: ShaderKind,
    /// Parameters in declaration order.
    pub params: Vec<ParamInfo>,
    /// True when the shader asks for derivatives (Du, Dv, Deriv, area, filterwidth,
    /// calculatenormal, filterstep, …), so renderers know to shade with dual numbers.
    pub uses_derivatives: bool,
}

impl ShaderMeta {
    /// The parameter called `name`.
    #[must_use]
    pub fn param(&self, name: &str) -> Option<&ParamInfo> {
        self.params.iter().find(|p| p.name == name)
    }
}

/// Why setting a parameter failed.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamError {
    /// No parameter of that name; lists the ones that exist.
    Unknown {
        /// Shader name.
        shader: String,
        /// The name asked for.
        name: String,
        /// Parameters the shader has.
        known: Vec<String>,
    },
    /// The value does not fit the parameter's type.
    Type {
        /// Parameter name.
        name: String,
        /// Expected type.
        expected: ParamType,
        /// What was given.
        got: ParamValue,
    },
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Unknown { shader, name, known } => {
                write!(f, "shader '{shader}' has no parameter '{name}' (parameters: {})", known.join(", "))
            }
            Self::Type { name, expected, got } => {
                write!(f, "parameter '{name}' is a {}, cannot take {got}", expected.keyword())
            }
        }
    }
}

impl std::error::Error for ParamError {}

/// Conversion between a Rust parameter field and a [`ParamValue`].
pub trait ParamField: Sized {
    /// The field as a value.
    fn to_value(&self) -> ParamValue;
    /// The field from a value (with float → triple promotion); `None` if the type is wrong.
    fn from_value(v: &ParamValue) -> Option<Self>;
}

impl ParamField for f64 {
    fn to_value(&self) -> ParamValue {
        ParamValue::Float(*self)
    }
    fn from_value(v: &ParamValue) -> Option<Self> {
        match v {
            ParamValue::Float(x) => Some(*x),
            _ => None,
        }
    }
}

impl ParamField for [f64; 3] {
    fn to_value(&self) -> ParamValue {
        ParamValue::Triple(*self)
    }
    fn from_value(v: &ParamValue) -> Option<Self> {
        match v {
            ParamValue::Triple(x) => Some(*x),
            ParamValue::Float(x) => Some([*x; 3]),
            _ => None,
        }
    }
}

impl ParamField for String {
    fn to_value(&self) -> ParamValue {
        ParamValue::String(self.clone())
    }
    fn from_value(v: &ParamValue) -> Option<Self> {
        match v {
            ParamValue::String(s) => Some(s.clone()),
            _ => None,
        }
    }
}

impl ParamField for [f64; 16] {
    fn to_value(&self) -> ParamValue {
        ParamValue::Matrix(*self)
    }
    fn from_value(v: &ParamValue) -> Option<Self> {
        match v {
            ParamValue::Matrix(m) => Some(*m),
            ParamValue::Float(x) => {
                let mut m = [0.0; 16];
                for i in 0..4 {
                    m[i * 5] = *x;
                }
                Some(m)
            }
            _ => None,
        }
    }
}

/// What every shader publishes: metadata and parameters by name.
pub trait Shader: Send + Sync {
    /// Name, kind and parameters.
    fn meta(&self) -> ShaderMeta;
    /// Current value of a parameter.
    fn param(&self, name: &str) -> Option<ParamValue>;
    /// Sets a parameter by name (float promotes to triples).
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError>;
}

/// A surface shader: computes the colour and opacity leaving a surface point.
pub trait SurfaceShader: Shader {
    /// Shades the points of `ctx` (live lanes in `e`). Generic in the number type: this is
    /// where type replacement happens.
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F>;

    /// The globals `shade` reads, through [`ShadingContext::globals`] or the context's own
    /// use of them in `illuminance`, `ambient` and friends. A renderer may leave the others
    /// holding any finite values. The default, every global, is always right; a shader that
    /// knows better (a compiled `.sl` shader from its IR) saves the renderer work.
    #[inline(always)]
    fn globals_read(&self) -> crate::globals::GlobalSet {
        crate::globals::GlobalSet::ALL
    }

    /// Runs `v` on the concrete shader. A closed set of shaders (an enum dispatching by
    /// `match`) overrides this to pass its variant, so a renderer's whole inner loop is
    /// monomorphized — and the shader inlined into it — per concrete shader, with the `match`
    /// paid once per loop instead of once per shading call.
    #[inline(always)]
    fn visit<V: SurfaceVisitor>(&self, v: V) -> V::Output
    where
        Self: Sized,
    {
        v.visit(self)
    }
}

/// Generic code to run on a concrete surface shader (see [`SurfaceShader::visit`]).
pub trait SurfaceVisitor {
    /// What the visit returns.
    type Output;
    /// Runs on shader `s`.
    fn visit<S: SurfaceShader>(self, s: &S) -> Self::Output;
}

/// A light shader: the light's colour and direction as seen from surface points `ps`.
pub trait LightShader: Shader {
    /// Evaluates the light for the points `ps` (live lanes in `e`).
    fn light<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F>;

    /// [`LightShader::light`] seeing the named spaces `spaces` — a light placed in a scene sees
    /// its own "shader" space (the space current at its `LightSource`) and the frame's named
    /// coordinate systems. Lights that name no space need not override it.
    #[inline(always)]
    fn light_in<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>, spaces: &Spaces) -> LightOutput<F> {
        let _ = spaces;
        self.light(e, ps)
    }

    /// How this light always emits, when that is known without evaluating it (`None`: it
    /// depends on the evaluation). The light loops use it to skip lights they cannot use —
    /// `illuminance` never evaluates an ambient light, `ambient()` never a directed one.
    #[inline(always)]
    fn emission(&self) -> Option<Emission> {
        None
    }

    /// The light's categories (RSL parameter `__category`: a comma-separated list), which
    /// `illuminance("category", …)` selects on; empty for none.
    #[inline(always)]
    fn category(&self) -> &str {
        ""
    }

    /// The light as data ([`LightData`]: what its `light` computes, for the `f32`-based float
    /// types bit for bit), when it is one of the kinds data can describe; `None` otherwise.
    #[inline(always)]
    fn data(&self) -> Option<LightData> {
        None
    }

    /// The machine code of [`LightShader::light`] at float type `F`, for compiled light loops
    /// to call ([`LightCode`]), when the light has code for `F` that they can call; `None`
    /// (the default) otherwise.
    #[inline(always)]
    fn code<F: ShadingFloat>(&self) -> Option<LightCode> {
        self.code_in::<F>(Spaces::standard())
    }

    /// [`LightShader::code`] of [`LightShader::light_in`] with `spaces`, which must outlive
    /// every use of the code (the pointer is kept in it).
    #[inline(always)]
    fn code_in<F: ShadingFloat>(&self, spaces: &Spaces) -> Option<LightCode> {
        let _ = spaces;
        None
    }
}

/// A displacement shader: moves P and sets N.
pub trait DisplacementShader: Shader {
    /// Returns the displaced `(P, N)`.
    fn displace<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> (Vec3<F>, Vec3<F>);
}

/// A volume shader (RSL `volume`: an atmosphere, interior or exterior): changes the light
/// travelling along a ray segment from `E` to `P` (`I = P − E`, its length the segment's) —
/// `entering` is the `Ci`/`Oi` arriving at `P` (the surface's result), the output what leaves
/// the segment towards `E`.
pub trait VolumeShader: Shader {
    /// The attenuated `Ci`, `Oi` of the live lanes of `e` (the context's globals are the
    /// segment's `P`, `I`, `E`).
    fn volume<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut Exec<F>,
        entering: SurfaceOutput<F>,
    ) -> SurfaceOutput<F>;
}

/// One pixel (or a vector of pixels) as an imager shader sees and leaves it.
#[allow(non_snake_case)]
#[derive(Clone, Copy, Debug)]
pub struct ImagerPixel<F> {
    /// The raster position of the pixel centre (`z` = 0).
    pub P: Vec3<F>,
    /// The filtered colour (premultiplied by coverage).
    pub Ci: Color<F>,
    /// The filtered opacity.
    pub Oi: Color<F>,
    /// The fraction of the pixel covered by geometry.
    pub alpha: F,
}

/// An imager shader (RSL `imager`): runs on the filtered pixels before exposure and
/// quantization.
pub trait ImagerShader: Shader {
    /// The pixel after the shader (its `Ci`, `Oi`, `alpha`; `P` as given), for the live lanes
    /// of `e`.
    fn image<F: ShadingFloat>(&self, e: &mut Exec<F>, pixel: ImagerPixel<F>) -> ImagerPixel<F>;

    /// [`ImagerShader::image`] for many chunks of pixels (chunk `k` live in the lanes of
    /// `masks[k]`), each replaced by its result; a back end that runs a batch faster than its
    /// chunks one by one (the interpreter decodes each op once per batch) overrides it.
    ///
    /// # Panics
    /// When `masks` is shorter than `pixels`.
    fn image_batch<F: ShadingFloat>(&self, pixels: &mut [ImagerPixel<F>], masks: &[F::Mask]) {
        assert!(masks.len() >= pixels.len(), "{} chunks, {} masks", pixels.len(), masks.len());
        for (px, &m) in pixels.iter_mut().zip(masks) {
            *px = self.image(&mut Exec::with_mask(m), *px);
        }
    }
}

/// Declares a shader's parameter struct with defaults, metadata and set/get by name.
///
/// ```
/// anysl_core::shader_params! {
///     /// A matte surface.
///     pub struct Matte: surface "matte" {
///         /// Ambient coefficient.
///         uniform float Ka = 1.0;
///         uniform float Kd = 1.0;
///         uniform color tint = [1.0, 1.0, 1.0];
///     }
/// }
/// use anysl_core::{Shader, ParamValue};
/// let mut m = Matte::default();
/// m.set_param("Kd", &ParamValue::Float(0.5)).unwrap();
/// assert_eq!(m.Kd, 0.5);
/// assert_eq!(m.meta().params.len(), 3);
/// assert!(m.set_param("Kx", &ParamValue::Float(0.5)).is_err());
/// ```
#[macro_export]
macro_rules! shader_params {
    (@rty float) => { f64 };
    (@rty color) => { [f64; 3] };
    (@rty point) => { [f64; 3] };
    (@rty vector) => { [f64; 3] };
    (@rty normal) => { [f64; 3] };
    (@rty string) => { ::std::string::String };
    (@rty matrix) => { [f64; 16] };
    (@pty float) => { $crate::ParamType::Float };
    (@pty color) => { $crate::ParamType::Color };
    (@pty point) => { $crate::ParamType::Point };
    (@pty vector) => { $crate::ParamType::Vector };
    (@pty normal) => { $crate::ParamType::Normal };
    (@pty string) => { $crate::ParamType::String };
    (@pty matrix) => { $crate::ParamType::Matrix };
    (@storage uniform) => { $crate::Storage::Uniform };
    (@storage varying) => { $crate::Storage::Varying };
    (@kind surface) => { $crate::ShaderKind::Surface };
    (@kind light) => { $crate::ShaderKind::Light };
    (@kind displacement) => { $crate::ShaderKind::Displacement };
    (@kind volume) => { $crate::ShaderKind::Volume };
    (@kind imager) => { $crate::ShaderKind::Imager };
    (
        $(#[$doc:meta])*
        $vis:vis struct $T:ident : $kind:ident $sname:literal $(uses_derivatives = $derivs:literal)? {
            $( $(#[$fdoc:meta])* $storage:ident $ty:ident $field:ident = $default:expr; )*
        }
    ) => {
        $(#[$doc])*
        #[allow(non_snake_case)]
        #[derive(Clone, Debug, PartialEq)]
        $vis struct $T {
            $( $(#[$fdoc])* pub $field: $crate::shader_params!(@rty $ty), )*
        }

        impl Default for $T {
            fn default() -> Self {
                Self { $( $field: ::core::convert::Into::into($default), )* }
            }
        }

        impl $crate::Shader for $T {
            fn meta(&self) -> $crate::ShaderMeta {
                let d = Self::default();
                $crate::ShaderMeta {
                    name: $sname.to_string(),
                    kind: $crate::shader_params!(@kind $kind),
                    params: vec![$(
                        $crate::ParamInfo {
                            name: stringify!($field).to_string(),
                            ty: $crate::shader_params!(@pty $ty),
                            array_len: None,
                            default: $crate::ParamField::to_value(&d.$field),
                            storage: $crate::shader_params!(@storage $storage),
                            output: false,
                        },
                    )*],
                    uses_derivatives: false $(|| $derivs)?,
                }
            }
            fn param(&self, name: &str) -> Option<$crate::ParamValue> {
                match name {
                    $( stringify!($field) => Some($crate::ParamField::to_value(&self.$field)), )*
                    _ => None,
                }
            }
            #[allow(unreachable_code, unused_variables)]
            fn set_param(&mut self, name: &str, value: &$crate::ParamValue) -> Result<(), $crate::ParamError> {
                match name {
                    $( stringify!($field) => {
                        self.$field = $crate::ParamField::from_value(value).ok_or_else(|| $crate::ParamError::Type {
                            name: name.to_string(),
                            expected: $crate::shader_params!(@pty $ty),
                            got: value.clone(),
                        })?;
                        Ok(())
                    } )*
                    _ => Err($crate::ParamError::Unknown {
                        shader: $sname.to_string(),
                        name: name.to_string(),
                        known: vec![$( stringify!($field).to_string(), )*],
                    }),
                }
            }
        }
    };
}

/// Every light shader is a [`LightSource`] for the shared light loops.
impl<T: LightShader> LightSource for T {
    #[inline(always)]
    fn source_emission(&self) -> Option<Emission> {
        self.emission()
    }
    #[inline(always)]
    fn source_category(&self) -> &str {
        self.category()
    }
    #[inline(always)]
    fn evaluate<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        self.light(e, ps)
    }
    #[inline(always)]
    fn source_data(&self) -> Option<LightData> {
        self.data()
    }
    #[inline(always)]
    fn source_code<F: ShadingFloat>(&self) -> Option<LightCode> {
        self.code::<F>()
    }
}
