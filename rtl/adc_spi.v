// adc_spi: SPI master for the 3-channel, 12-bit phase-current ADC, converting back to back,
// with per-frame overcurrent and plausibility checks.
//
// Three simultaneous-sampling serial ADCs (AD7476 / ADS7886 style) share one SCLK and one
// active-low CS; each returns its frame on its own MISO line.  Full description, timing
// diagram and resources: docs/blocks/adc_spi.md.  Bit-accurate model (cycle exact):
// gen/empc/rtlmodel/adc_spi.py (AdcSpiCycle).
//
// Frame schedule.  Frames run continuously on a grid of TF clocks (FRAME_PERIOD; 0 = the
// shortest period a frame allows, rounded up to even when AVG_LOG2 > 0) that is re-phased
// at every PWM period boundary (`period_start`, cycle 0 of the period, reloads the grid at
// its edge): grid points at cycles t = G0 + m*TF (m = 0, 1, .., 1 <= G0 <= TF), placed so
// that the 2^AVG_LOG2 "window" frames
// m = M0 .. M0 + 2^AVG_LOG2 - 1 start (CS falls) symmetrically about the PWM centre
// (cycle HALF_PERIOD, where pwm_center's adc_trig is): at HALF_PERIOD + (j - (2^K-1)/2)*TF.
// A frame starts at a grid point unless the previous one is still busy (only possible at
// the first grid point after a boundary, never in the window).  One gap per PWM period
// (at the boundary) re-phases the grid; frames run (and are checked) with the bridges
// off too, and before the first boundary (no window then).
//
// SPI protocol (CPOL = 1: SCLK idles high; data launched by the slave on CS falling
// (bit 0) and on SCLK falling edges 1..FRAME_BITS-1; FRAME_BITS SCLK cycles per frame).
// Frame, MSB first: LEAD_ZEROS zeros | ADC_BITS code bits MSB first | trailing bits.
// Timing in clk edges after the edge E0 that starts a frame (frame accepted in cycle a,
// E0 = end of cycle a): CS falls at E0, SCLK falling edge k (k = 1..FRAME_BITS) at
// E0 + 2*k*SCLK_DIV, rising edge k at E0 + (2*k+1)*SCLK_DIV.  Bit k is latched from the
// synchronised MISO (sync_2ff) at E0 + 2*k*SCLK_DIV + SAMPLE_DELAY (pin sampled
// SAMPLE_DELAY - 2 clk after the launch).  CS rises at E0 + T_CS,
// T_CS = max((2*FRAME_BITS+2)*SCLK_DIV, 2*(FRAME_BITS-1)*SCLK_DIV + SAMPLE_DELAY + 1),
// and stays high >= CS_QUIET clk.  VL = 2*(FRAME_BITS-1)*SCLK_DIV + SAMPLE_DELAY + 2
// (defaults: 67).  "At edge E0 + k" = registered there, visible in the cycle after it.
//
// Every frame (at edge E0 + VL; `fvalid` high for that one cycle):
//   code0..2   raw codes (one edge earlier, E0 + VL - 1)
//   oc         pulse: some |code_i - offset_i| > oc_thr (unsaturated difference); oc_ch held
//   frame_err  pulse: a leading-zero bit read 1 (broken/floating MISO, misaligned frame)
//   stuck      level: in each of the last STUCK_PERSIST frames some channel's code was
//              0 or 2^ADC_BITS-1 (a rail); cleared by the first frame without a rail
//   sum_err    level: |d0 + d1 + d2| > sum_thr (d_i = code_i - offset_i) in each of the last
//              SUM_PERSIST frames; at edge E0 + VL + SW (SW = ADC_BITS + 3), 15 clocks after
//              fvalid (the check runs bit-serially)
//   Latency overcurrent: the frame's last SCLK rising edge is edge E0 + (2*FRAME_BITS+1)*
//   SCLK_DIV, oc comes at edge E0 + VL: SAMPLE_DELAY + 2 - 3*SCLK_DIV clocks later
//   (defaults: 1).  mpc_axis: trip is combinational, pwm_center registers the outputs:
//   bridge pins off one more clock later (defaults: 2 clocks after the last SCLK rising edge).
// Controller sample (once per PWM period): `valid` pulses, cur0..2 = sat(round-half-up
//   mean of the window frames' code_i - offset_i, CUR_W), sat with valid.
//   AVG_LOG2 = 0: the centre frame alone, valid at edge E0 + VL of the frame started at
//   `trig`: bit-exact and cycle-exact the former single conversion (trig + 68 clocks).
//   AVG_LOG2 = K > 0: accumulated bit-serially, valid at edge E0_last + VL + AW + 1 of the
//   last window frame (AW = ADC_BITS + 1 + K): (2^K-1)*TF/2 + VL + AW + 2 clocks after the
//   trig cycle (defaults K = 2, TF = 74: 195).
// Period sums (for the CPU, PiKRON style): psum_i = sum of code_i - offset_i over the
//   frames whose `fvalid` cycle - 1 lies in the PWM period, pcount = their number; both
//   loaded together once the period has ended (at the boundary, or after the running
//   serial pass); pcount saturates at 2^PCNT_W-1 (then the sums stop adding: sum/count stays
//   the exact mean of the counted frames).
// Frozen ADC: a period counts as frozen if the bridges were on in every cycle of it,
//   >= 2 frames ended in it and some channel's frame (all FRAME_BITS bits) equalled the
//   previous frame in every one of them; `frozen` (level) is set at the boundary ending
//   the FROZEN_PERIODS-th consecutive frozen period, cleared at the next boundary that
//   ends a non-frozen period (bridges off for a clock counts as non-frozen).
// Centre check: `trig` (pwm_center adc_trig) must come at cycle HALF_PERIOD of the period;
//   otherwise, and when a boundary cuts a window (a sync restart), trig_miss pulses (next
//   cycle) and the saturating miss_cnt counts.  A cut window gives no `valid`.
//
// Offsets: offset_i resets to OFFSET_RESET; off_we[i] loads off_wdata unless a calibration
// runs or bridges_on (refused: `refused` set).  cal_start (pulse) starts a calibration,
// refused while bridges_on; a running calibration is aborted (cal_busy falls, cal_done stays
// 0, `refused` set) in the cycle after bridges_on rises.  The channels are averaged one
// after the other (0, 1, 2), each over the next 2^CAL_LOG2 frames *accepted after*
// cal_start (resp. after the previous channel finished); a channel's offset is loaded with
// the round-half-up mean in the fvalid cycle of its last frame; after channel 2 cal_done
// is set (sticky until the next cal_start).  `refused` is sticky until refused_clear.
//
// Parameters: ADC_BITS, FRAME_BITS, LEAD_ZEROS (>= 1), SCLK_DIV (>= 1), SAMPLE_DELAY (>= 3),
//   CS_QUIET (>= 1), HALF_PERIOD (pwm_center's P), AVG_LOG2 (K), FRAME_PERIOD (TF, 0 = auto),
//   CAL_LOG2 (>= 1), CUR_W (>= 2), MISS_W, OFFSET_RESET, PCNT_W (period frame counter),
//   SUM_PERSIST, STUCK_PERSIST (>= 1, frames), FROZEN_PERIODS (>= 1, PWM periods), NAXES (1..4),
//   STAGGER (carrier offset between neighbouring axes, clk, a multiple of TF; NAXES > 1).
//   Illegal combinations stop the elaboration (module adc_spi_bad_parameters).
// Resources (Yosys synth_xilinx xc6s, defaults): see docs/blocks/adc_spi.md.
// NAXES > 1 (docs/blocks/adc_spi.md "NAXES > 1"): one frame engine (one SCLK, one CS, one grid,
//   one capture schedule) serves NAXES axes of 3 converters each (miso[3a+i] = axis a, phase i).
//   Every per-axis port is a vector, axis a at [a*W +: W] (NAXES = 1: today's ports, bit- and
//   cycle-exact).  Axis a's carrier is axis 0's delayed by a*STAGGER clk (pwm_center PHASE,
//   `EMPC_PWM_STAGGER_<NAXES>, a whole number of frames): its window frames are the grid points
//   centred on its own centre.  The grid is re-phased once per PWM period at cycle R of axis 0's
//   period (R = the first clock after the last axis's last serial pass, where no window is); axis 0's
//   period_start only re-loads the grid if it is out of phase (a sync restart: a "jump", which cuts
//   the windows open then: miss per axis, no valid).  Everything per frame after the capture is
//   replicated per axis (codes, checks, period accumulators, serial pass adders, calibration,
//   offsets, frozen, centre check), except the three window accumulators: the axes' windows are
//   disjoint (STAGGER >= 2^AVG_LOG2 frames), so one set serves all axes (g_wsh).  Each axis's
//   outputs come at the single-axis latencies after its own frames / boundaries, and depend only
//   on its own inputs and MISO lines.
// Reset (synchronous, rst): cs_n = 1, sclk = 1, idle, grid restarts (no window until the
//   first period_start), all outputs, sums, counters and flags 0, offsets = OFFSET_RESET,
//   calibration idle.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module adc_spi #(
    parameter integer ADC_BITS       = `EMPC_ADC_BITS,
    parameter integer FRAME_BITS     = 16,
    parameter integer LEAD_ZEROS     = 4,
    parameter integer SCLK_DIV       = 2,
    parameter integer SAMPLE_DELAY   = 5,
    parameter integer CS_QUIET       = 5,
    parameter integer HALF_PERIOD    = `EMPC_PWM_HALF_PERIOD,
    parameter integer AVG_LOG2       = 2,
    parameter integer FRAME_PERIOD   = 0,
    parameter integer CAL_LOG2       = 10,
    parameter integer CUR_W          = ADC_BITS + 1,
    parameter integer MISS_W         = 8,
    parameter integer OFFSET_RESET   = `EMPC_ADC_OFFSET,
    parameter integer PCNT_W         = 7,
    parameter integer SUM_PERSIST    = `EMPC_ADC_SUM_FRAMES,
    parameter integer STUCK_PERSIST  = `EMPC_ADC_STUCK_FRAMES,
    parameter integer FROZEN_PERIODS = `EMPC_ADC_FROZEN_PERIODS,
    parameter integer NAXES          = 1,
    parameter integer STAGGER        = (NAXES == 2) ? `EMPC_PWM_STAGGER_2 : (NAXES == 3) ? `EMPC_PWM_STAGGER_3
                                     : (NAXES == 4) ? `EMPC_PWM_STAGGER_4 : 0
) (
    input  wire                           clk,
    input  wire                           rst,
    // PWM timing and state (per axis)
    input  wire [NAXES-1:0]               period_start,  // PWM period boundary (1 clk)
    input  wire [NAXES-1:0]               trig,          // PWM centre (1 clk): checked
    input  wire [NAXES-1:0]               bridges_on,    // outputs may switch
    output wire                           busy,          // a frame is in progress (shared)
    output wire [NAXES-1:0]               trig_miss,
    output wire [NAXES*MISS_W-1:0]        miss_cnt,
    // SPI pins (one SCLK, one CS; three MISO lines per axis)
    output reg                            cs_n,
    output reg                            sclk,
    input  wire [3*NAXES-1:0]             miso,          // asynchronous
    // every frame
    output reg                            fvalid,        // shared: the frame is common
    output wire [NAXES*ADC_BITS-1:0]      code0,
    output wire [NAXES*ADC_BITS-1:0]      code1,
    output wire [NAXES*ADC_BITS-1:0]      code2,
    output wire [NAXES-1:0]               frame_err,
    input  wire [NAXES*ADC_BITS-1:0]      oc_thr,
    output wire [NAXES-1:0]               oc,
    output wire [3*NAXES-1:0]             oc_ch,
    input  wire [NAXES*ADC_BITS-1:0]      sum_thr,
    output wire [NAXES-1:0]               sum_err,
    output wire [NAXES-1:0]               stuck,
    output wire [NAXES-1:0]               frozen,
    // controller sample, once per PWM period (of the axis)
    output wire [NAXES-1:0]               valid,
    output wire signed [NAXES*CUR_W-1:0]  cur0,
    output wire signed [NAXES*CUR_W-1:0]  cur1,
    output wire signed [NAXES*CUR_W-1:0]  cur2,
    output wire [NAXES-1:0]               sat,
    // sums of the last complete PWM period (offset-corrected)
    output wire signed [NAXES*(ADC_BITS+PCNT_W+1)-1:0] psum0,
    output wire signed [NAXES*(ADC_BITS+PCNT_W+1)-1:0] psum1,
    output wire signed [NAXES*(ADC_BITS+PCNT_W+1)-1:0] psum2,
    output wire [NAXES*PCNT_W-1:0]        pcount,
    // offsets
    input  wire [3*NAXES-1:0]             off_we,
    input  wire [NAXES*ADC_BITS-1:0]      off_wdata,
    output wire [NAXES*ADC_BITS-1:0]      offset0,
    output wire [NAXES*ADC_BITS-1:0]      offset1,
    output wire [NAXES*ADC_BITS-1:0]      offset2,
    input  wire [NAXES-1:0]               cal_start,
    output wire [NAXES-1:0]               cal_busy,
    output wire [NAXES-1:0]               cal_done,
    output wire [NAXES-1:0]               refused,       // sticky: cal_start / offset write refused, calibration aborted
    input  wire [NAXES-1:0]               refused_clear
);
    // ---------------------------------------------------------------- sizes
    localparam integer HB_END = 2 * FRAME_BITS + 2;          // half-bit periods per frame
    localparam integer HB_W   = $clog2(HB_END + 1);
    localparam integer DIV_W  = (SCLK_DIV > 1) ? $clog2(SCLK_DIV) : 1;
    localparam integer PIPE_N = SAMPLE_DELAY - 1;             // strobe delay stages
    localparam integer Q_W    = (CS_QUIET > 1) ? $clog2(CS_QUIET) : 1;
    localparam integer D_W    = ADC_BITS + 1;                  // code - offset, exact
    localparam integer ACC_W  = ADC_BITS + CAL_LOG2;
    localparam integer CODE_MSB = FRAME_BITS - 1 - LEAD_ZEROS;
    localparam integer PSW    = ADC_BITS + 1 + PCNT_W;         // period sum width

    localparam integer HB_LAST_I    = HB_END - 1;
    localparam integer HB_LLAUNCH_I = 2 * FRAME_BITS - 2;     // last launching half-bit
    localparam integer DIV_LAST_I   = SCLK_DIV - 1;
    localparam integer Q_LAST_I     = (CS_QUIET > 1) ? CS_QUIET - 2 : 0;
    localparam [HB_W-1:0]   HB_LAST    = HB_LAST_I[HB_W-1:0];
    localparam [HB_W-1:0]   HB_LLAUNCH = HB_LLAUNCH_I[HB_W-1:0];
    localparam integer HB_CB0_I = 2 * (LEAD_ZEROS + 1), HB_CB1_I = 2 * (LEAD_ZEROS + ADC_BITS - 1);
    localparam [HB_W-1:0]   HB_CB0 = HB_CB0_I[HB_W-1:0];     // launch half-bits of the code bits after the MSB
    localparam [HB_W-1:0]   HB_CB1 = HB_CB1_I[HB_W-1:0];
    localparam [DIV_W-1:0]  DIV_LAST   = DIV_LAST_I[DIV_W-1:0];
    localparam [Q_W-1:0]    Q_LAST     = Q_LAST_I[Q_W-1:0];
    localparam [CAL_LOG2-1:0] CAL_LAST = {CAL_LOG2{1'b1}};

    localparam [1:0] S_IDLE = 2'd0, S_XFER = 2'd1, S_WAIT = 2'd2, S_QUIET = 2'd3;

    // serial pass after every frame: window (AW), sum check (SW), period sums (PSW) bits
    localparam integer AW   = D_W + AVG_LOG2;
    localparam integer SW   = D_W + 2;                         // |s| <= 3*(2^B-1), s -/+ thr fit
    localparam integer PL_A = (AVG_LOG2 > 0) ? AW + 1 : 0;
    localparam integer PL_B = (SW > PSW) ? SW : PSW;
    localparam integer PL   = (PL_A > PL_B) ? PL_A : PL_B;     // pass length, clocks

    // ------------------------------------------------------------ schedule
    localparam integer T_CS_A = (2 * FRAME_BITS + 2) * SCLK_DIV;
    localparam integer T_CS_B = 2 * (FRAME_BITS - 1) * SCLK_DIV + SAMPLE_DELAY + 1;
    localparam integer T_CS   = (T_CS_A > T_CS_B) ? T_CS_A : T_CS_B;
    localparam integer VL     = 2 * (FRAME_BITS - 1) * SCLK_DIV + SAMPLE_DELAY + 2;
    localparam integer MINP   = (T_CS + CS_QUIET > VL + 1) ? T_CS + CS_QUIET : VL + 1;
    localparam integer TF     = (FRAME_PERIOD > 0) ? FRAME_PERIOD
                              : (AVG_LOG2 > 0) ? MINP + (MINP % 2) : MINP;
    localparam integer NW     = 1 << AVG_LOG2;                 // window frames
    localparam integer WLEAD  = ((NW - 1) * TF) / 2;           // first window frame before the centre
    // Grid coordinates: cycle 0 = the cycle that (re)loads the grid (NAXES = 1: period_start;
    // NAXES > 1: cycle R of axis 0's period).  Axis a's centre is grid cycle C0 + a*STAGGER.
    // NAXES > 1: R = the first clock after the last axis's last window pass, so that pass ends in
    // grid cycle 2P - 1 and every window lies inside one grid run.
    localparam integer P2     = 2 * HALF_PERIOD;
    localparam integer R_REPH = (NAXES > 1) ? (HALF_PERIOD + (NAXES - 1) * STAGGER + WLEAD + VL + PL + 1) % P2 : 0;
    localparam integer C0     = (NAXES > 1) ? P2 - ((NAXES - 1) * STAGGER + WLEAD + VL + PL + 1) : HALF_PERIOD;
    localparam integer T0     = C0 - WLEAD;                    // axis 0's first window frame, grid cycle
    localparam integer G0     = (T0 % TF == 0) ? TF : T0 % TF; // first grid point (>= 1)
    localparam integer M0     = (T0 - G0) / TF;                // grid index of axis 0's window
    localparam integer GC_C   = ((G0 - C0) % TF + TF) % TF;    // gc at every axis's centre
    localparam integer GP_MAXI = (2 * HALF_PERIOD) / TF + 2;
    localparam integer GP_W   = $clog2(GP_MAXI + 1);
    localparam integer GC_W   = $clog2(TF);
    localparam [GP_W-1:0] GP_MAX = GP_MAXI[GP_W-1:0];
    localparam [GC_W-1:0] GC_CEN  = GC_C[GC_W-1:0];
    localparam integer GC_G0I = G0 - 1;
    localparam [GC_W-1:0] GC_G0   = GC_G0I[GC_W-1:0];          // gc after a reload
    localparam integer GC_TOPI = TF - 1;
    localparam [GC_W-1:0] GC_TOP  = GC_TOPI[GC_W-1:0];
    // NAXES > 1: grid state (gc, gp) in grid cycle x >= 1 after a reload: gc = (G0 - x) mod TF,
    // gp = x <= G0 ? 0 : (x - G0 - 1) / TF + 1.  Terminal state = grid cycle 2P (reload to G0 - 1, 0);
    // axis 0's boundary is grid cycle Y0 = 2P - R (2P if R = 0): the state expected there (J) and
    // the one loaded at its edge when it differs (L = grid cycle Y0 + 1).
    localparam integer Y0     = P2 - R_REPH;
    localparam integer Y1     = (Y0 == P2) ? 1 : Y0 + 1;
    localparam integer GC_TI  = ((G0 - P2) % TF + TF) % TF;
    localparam integer GP_TI  = (P2 - G0 - 1) / TF + 1;
    localparam integer GC_JI  = ((G0 - Y0) % TF + TF) % TF;
    localparam integer GP_JI  = (Y0 <= G0) ? 0 : (Y0 - G0 - 1) / TF + 1;
    localparam integer GC_LI  = ((G0 - Y1) % TF + TF) % TF;
    localparam integer GP_LI  = (Y1 <= G0) ? 0 : (Y1 - G0 - 1) / TF + 1;
    localparam integer PJ_W = $clog2(PL + 1);
    localparam integer PJ_LASTI = PL - 1, PJ_SIGNI = SW - 1, PJ_KM1I = (AVG_LOG2 > 0) ? AVG_LOG2 - 1 : 0;
    localparam [PJ_W-1:0] PJ_LAST = PJ_LASTI[PJ_W-1:0];
    localparam [PJ_W-1:0] PJ_SIGN = PJ_SIGNI[PJ_W-1:0];
    localparam [PJ_W-1:0] PJ_WEND = AW[PJ_W-1:0];        // = window width: the window's bits are in
    localparam [PJ_W-1:0] PJ_KM1  = PJ_KM1I[PJ_W-1:0];   // bit K-1: the rounding half
    localparam [PJ_W-1:0] PJ_PSW  = PSW[PJ_W-1:0];
    localparam [PJ_W-1:0] PJ_AB   = ADC_BITS[PJ_W-1:0];
    localparam integer JD_W = $clog2(D_W), JT_W = $clog2(ADC_BITS);
    localparam integer D_TOPI = D_W - 1;
    localparam [JD_W-1:0] JD_TOP = D_TOPI[JD_W-1:0];
    localparam [PCNT_W-1:0] PCNT_MAX = {PCNT_W{1'b1}};
    // persistence (sum check, rails, frozen): thermometer codes, bit k = "at least k consecutive bad
    // frames (periods) before this one", bit 0 constant 1: a shift and a clear, no counter (saturates
    // by itself); the output trips on a bad one with bit PERSIST - 1 set
    localparam integer SP_T = SUM_PERSIST - 1, KP_T = STUCK_PERSIST - 1, FZ_T = FROZEN_PERIODS - 1;
    localparam [SP_T:0] SP_ONE = 1;
    localparam [KP_T:0] KP_ONE = 1;
    localparam [FZ_T:0] FZ_ONE = 1;
    localparam integer PCNT_MAXI = (1 << PCNT_W) - 1;

    generate if (LEAD_ZEROS < 1 || LEAD_ZEROS + ADC_BITS > FRAME_BITS || SCLK_DIV < 1 || SAMPLE_DELAY < 3 ||
                 CS_QUIET < 1 || CAL_LOG2 < 1 || CUR_W < 2 || TF < MINP || (AVG_LOG2 > 0 && TF % 2 != 0) ||
                 M0 < 1 || PL + 2 > TF || (NAXES == 1 && T0 + NW * TF + VL + PL + 2 > 2 * HALF_PERIOD) ||
                 PCNT_MAXI < (2 * HALF_PERIOD - 1) / TF + 1 || SUM_PERSIST < 1 || STUCK_PERSIST < 1 ||
                 FROZEN_PERIODS < 1 || AVG_LOG2 < 0 || NAXES < 1 || NAXES > 4 ||
                 (NAXES > 1 && (STAGGER < TF || STAGGER % TF != 0 || C0 <= WLEAD)))
    begin : g_bad_params
        adc_spi_bad_parameters u_error ();     // no such module: elaboration stops here
    end endgenerate

    // ------------------------------------------------------------ MISO sync
    wire [3*NAXES-1:0] miso_s;
    sync_2ff #(.WIDTH(3 * NAXES), .STAGES(2)) u_sync_miso (
        .clk(clk), .rst(rst), .d(miso), .q(miso_s)
    );

    // ------------------------------------------------------------ frame grid
    // gc counts down to the next grid point (0 = grid point now), gp counts the grid
    // points of this grid run so far.  NAXES = 1: period_start reloads both at its edge, so
    // the new grid has its first point G0 >= 1 cycles after the boundary cycle (in the boundary
    // cycle itself the old grid still applies: no multiplexer in front of the counters).
    // NAXES > 1: the terminal state (grid cycle 2P) reloads them the same way; axis 0's
    // period_start loads the state of the cycle after it only if they are out of phase (g_jump).
    reg  [GC_W-1:0] gc;
    reg  [GP_W-1:0] gp;
    wire            go     = (gc == {GC_W{1'b0}});
    wire            g_jump;                // NAXES > 1: grid re-loaded out of phase (cuts open windows)
    // -------------------------------------------------------- frame control
    reg [1:0]        st;
    reg [DIV_W-1:0]  dcnt;
    reg [HB_W-1:0]   hb;
    reg [Q_W-1:0]    qcnt;
    reg              lstb;                 // bit launched at the previous edge
    reg              llast;                // ... and it was the last bit of the frame
    reg [PIPE_N-1:0] spipe;                // lstb delayed; spipe[PIPE_N-1] = capture now
    reg [PIPE_N-1:0] lpipe;                // llast delayed: the last capture
    reg              lcb;                  // bit launched at the previous edge is a code bit after the MSB
    reg [PIPE_N-1:0] cpipe;                // lcb delayed
    reg              all_cap;              // every bit of the frame captured
    reg              capdone;              // last bit captured at the previous edge
    reg              st_a;                 // stage A registered (codes, differences)

    wire cap      = spipe[PIPE_N-1];
    wire cap_last = lpipe[PIPE_N-1];
    wire accept   = go & ~busy;
    wire [HB_W-1:0] hb_n = hb + 1'b1;

    assign busy = (st != S_IDLE) | capdone | st_a;

    generate
        if (NAXES == 1) begin : g_grid1
            assign g_jump = 1'b0;
            always @(posedge clk) begin
                if (rst) begin
                    gc <= GC_TOP;
                    gp <= GP_MAX;          // no window before the first period_start
                end else begin
                    gc <= period_start[0] ? GC_G0 : go ? GC_TOP : gc - 1'b1;
                    gp <= period_start[0] ? {GP_W{1'b0}} : (go && gp != GP_MAX) ? gp + 1'b1 : gp;
                end
            end
        end else begin : g_gridn
            localparam [GC_W-1:0] GC_T = GC_TI[GC_W-1:0], GC_J = GC_JI[GC_W-1:0], GC_L = GC_LI[GC_W-1:0];
            localparam [GP_W-1:0] GP_T = GP_TI[GP_W-1:0], GP_J = GP_JI[GP_W-1:0], GP_L = GP_LI[GP_W-1:0];
            wire g_term = (gc == GC_T) && (gp == GP_T);
            assign g_jump = period_start[0] && !((gc == GC_J) && (gp == GP_J));
            always @(posedge clk) begin
                if (rst) begin
                    gc <= GC_TOP;
                    gp <= GP_MAX;          // no window before axis 0's first period_start
                end else begin
                    gc <= g_jump ? GC_L : g_term ? GC_G0 : go ? GC_TOP : gc - 1'b1;
                    gp <= g_jump ? GP_L : g_term ? {GP_W{1'b0}} : (go && gp != GP_MAX) ? gp + 1'b1 : gp;
                end
            end
        end
    endgenerate
    always @(posedge clk) begin
        if (rst) begin
            st        <= S_IDLE;
            cs_n      <= 1'b1;
            sclk      <= 1'b1;
            dcnt      <= {DIV_W{1'b0}};
            hb        <= {HB_W{1'b0}};
            qcnt      <= {Q_W{1'b0}};
            lstb      <= 1'b0;
            llast     <= 1'b0;
            lcb       <= 1'b0;
        end else begin
            lstb      <= 1'b0;
            llast     <= 1'b0;
            lcb       <= 1'b0;
            case (st)
                S_IDLE: if (accept) begin
                    cs_n <= 1'b0;                   // conversion start, bit 0 launched
                    sclk <= 1'b1;
                    dcnt <= {DIV_W{1'b0}};
                    hb   <= {HB_W{1'b0}};
                    lstb <= 1'b1;
                    st   <= S_XFER;
                end
                S_XFER: begin
                    if (dcnt == DIV_LAST) begin
                        dcnt <= {DIV_W{1'b0}};
                        hb   <= hb_n;
                        if (hb == HB_LAST) begin
                            // SCLK has been high for SCLK_DIV clk after its last rising edge
                            if (all_cap) begin
                                cs_n <= 1'b1;
                                qcnt <= {Q_W{1'b0}};
                                st   <= (CS_QUIET > 1) ? S_QUIET : S_IDLE;
                            end else begin
                                st   <= S_WAIT;
                            end
                        end else begin
                            sclk <= hb_n[0];        // half-bits 0,1 high (CS setup), then low/high
                            lstb <= ~hb_n[0] && (hb_n <= HB_LLAUNCH);
                            lcb  <= ~hb_n[0] && (hb_n >= HB_CB0) && (hb_n <= HB_CB1);
                            llast <= (hb_n == HB_LLAUNCH);
                        end
                    end else begin
                        dcnt <= dcnt + 1'b1;
                    end
                end
                S_WAIT: if (all_cap) begin           // SAMPLE_DELAY > 4*SCLK_DIV - 1 only
                    cs_n <= 1'b1;
                    qcnt <= {Q_W{1'b0}};
                    st   <= (CS_QUIET > 1) ? S_QUIET : S_IDLE;
                end
                default: begin                       // S_QUIET
                    qcnt <= qcnt + 1'b1;
                    if (qcnt == Q_LAST) st <= S_IDLE;
                end
            endcase
        end
    end

    // ------------------------------------------- sample-strobe delay + capture
    generate
        if (PIPE_N > 1) begin : g_pipe
            always @(posedge clk) begin
                if (rst) begin
                    spipe <= {PIPE_N{1'b0}};
                    lpipe <= {PIPE_N{1'b0}};
                    cpipe <= {PIPE_N{1'b0}};
                end else begin
                    spipe <= {spipe[PIPE_N-2:0], lstb};
                    lpipe <= {lpipe[PIPE_N-2:0], llast};
                    cpipe <= {cpipe[PIPE_N-2:0], lcb};
                end
            end
        end else begin : g_pipe1
            always @(posedge clk) begin
                if (rst) begin
                    spipe <= 1'b0;
                    lpipe <= 1'b0;
                    cpipe <= 1'b0;
                end else begin
                    spipe <= lstb;
                    lpipe <= llast;
                    cpipe <= lcb;
                end
            end
        end
    endgenerate

    // capture flags (shared): every bit of the frame captured, last capture, stage A
    always @(posedge clk) begin
        if (rst) begin
            all_cap <= 1'b0;
            capdone <= 1'b0;
            st_a    <= 1'b0;
            fvalid  <= 1'b0;
        end else begin
            capdone <= cap_last;
            if (accept)
                all_cap <= 1'b0;
            else if (cap_last)
                all_cap <= 1'b1;
            st_a   <= capdone;
            fvalid <= st_a;
        end
    end

    // ---------------------- stage B: overcurrent
    // |d| > thr on the registered difference: e = d ^ sign (= |d| - sign), so
    // |d| > thr <=> (d >= 0) ? e > thr : e >= thr <=> thr - e - 1 + ~sign < 0, i.e. no
    // carry out of thr + ~e + ~sign.  Written as one two-operand adder
    // {thr, 1} + {~e, ~sign} (the carry-in in bit 0): thr is the carry chain's DI and
    // d, sign, thr fit one LUT per bit (a three-operand form cost ~30 LUTs more in the top)
    function oc_f;
        input [D_W-1:0] d;
        input [ADC_BITS-1:0] thr;
        reg [ADC_BITS-1:0] e;
        reg [ADC_BITS+1:0] t;
        begin
            e = d[ADC_BITS-1:0] ^ {ADC_BITS{d[D_W-1]}};
            t = {1'b0, thr, 1'b1} + {1'b0, ~e, ~d[D_W-1]};
            oc_f = ~t[ADC_BITS+1];
        end
    endfunction

    // ------------------------------------------------ cur = sat(d, CUR_W)
    function [CUR_W:0] satf;               // {saturated, value}
        input [D_W-1:0] d;
        /* verilator lint_off UNUSEDSIGNAL */ // only the low CUR_W bits: the sign-extended value
        reg [CUR_W+D_W-1:0] x;
        /* verilator lint_on UNUSEDSIGNAL */
        reg fit;
        integer i;
        begin
            x = {{CUR_W{d[D_W-1]}}, d};                // sign-extended
            fit = 1'b1;                                // fits iff the bits from CUR_W-1 up equal the sign
            for (i = CUR_W - 1; i < D_W; i = i + 1)
                if (d[i] != d[D_W-1]) fit = 1'b0;
            satf = fit ? {1'b0, x[CUR_W-1:0]}
                 : {1'b1, d[D_W-1] ? {1'b1, {(CUR_W-1){1'b0}}} : {1'b0, {(CUR_W-1){1'b1}}}};
        end
    endfunction

    // ---------------------- serial pass after every frame: window mean, sum check, period sums
    // From the cycle after stage B, bit j = 0..PL-1 of the three differences (LSB first,
    // sign-extended) passes one per clock through 1-bit adders: the window accumulators
    // (preset 2^(K-1) at the first window frame: their top bits are the round-half-up
    // mean), the period accumulators and s = d0 + d1 + d2 with the two compares
    // s - thr - 1 >= 0 and s + thr < 0 (|s| > thr), whose signs are known at j = SW-1.
    // The accumulators are shift registers that rotate once per pass (flip-flops, no LUTs).
    // The bit counter is shared (every axis passes the same frame); the adders are per axis.
    reg              pbusy;
    reg [PJ_W-1:0]   pj;
    // the pass adders' carries clear at the pass start and step in the pass: one clear net and one
    // enable net for every axis (flip-flop reset / enable pins), so a carry's LUT sees only its data
    wire             p_clr = rst | st_a;
    wire             p_sce = pbusy & ~st_a & (pj == PJ_SIGN);   // the sum check's sign bit
    // jd = min(pj, D_W - 1) (the sign extension), a register stepped with pj: the bit selects of
    // the three differences start at a flip-flop, not behind a compare of pj (worst path of the drive)
    reg  [JD_W-1:0]  jd;
    always @(posedge clk) begin
        if (rst) begin
            pbusy <= 1'b0;
            pj    <= {PJ_W{1'b0}};
            jd    <= {JD_W{1'b0}};
        end else if (st_a) begin                            // pass start (stage B)
            pbusy <= 1'b1;
            pj    <= {PJ_W{1'b0}};
            jd    <= {JD_W{1'b0}};
        end else if (pbusy) begin
            pj <= pj + 1'b1;
            if (jd != JD_TOP) jd <= jd + 1'b1;
            if (pj == PJ_LAST) pbusy <= 1'b0;
        end
    end

    // ------------------------------------------- one window accumulator for all axes
    // NAXES > 1 with AVG_LOG2 > 0 and STAGGER >= 2^K frames: the axes' window frames are disjoint
    // ranges of the grid index gp (axis a's: MN .. MN + 2^K - 1, MN = M0 + a*STAGGER/TF), and gp steps
    // by one per grid point between the reloads (the terminal one lies after every window, a jump
    // closes every window).  A window frame is therefore counted (p_win) for one axis at most, and
    // between an axis's first and last counted window frame no other axis counts one: the three
    // window accumulators, preset at every first window frame, serve all axes (the per-axis
    // `valid`, `sat`, `cur` registers load from them at their axis's last frame, as before).
    localparam integer WSHARE = (NAXES > 1 && AVG_LOG2 > 0 && STAGGER >= NW * TF) ? 1 : 0;
    wire [NAXES-1:0]   wx_win, wx_first;   // per axis: this pass is a window frame / the first one
    wire [3*NAXES-1:0] wx_db;              // per axis: the differences' bits of this pass
    wire [CUR_W:0]     wsh0, wsh1, wsh2;   // satf of the shared window means
    generate
        if (WSHARE != 0) begin : g_wsh
            wire [AW-AVG_LOG2-1:0] accw0, accw1, accw2;
            reg  [2:0]    dbw;
            reg           any_win, any_first;
            integer       k;
            always @(*) begin
                dbw       = 3'b000;
                any_win   = 1'b0;
                any_first = 1'b0;
                for (k = 0; k < NAXES; k = k + 1) begin
                    dbw       = dbw | (wx_db[3 * k +: 3] & {3{wx_win[k]}});
                    any_win   = any_win | wx_win[k];
                    any_first = any_first | (wx_win[k] & wx_first[k]);
                end
            end
            adc_win_acc #(.AW(AW), .K(AVG_LOG2)) u_acc (
                .clk(clk), .rst(rst), .p_clr(p_clr), .st_a(st_a),
                .step_en(pbusy && any_win && pj < PJ_WEND), .first(any_first), .km1(pj == PJ_KM1), .db(dbw),
                .mean0(accw0), .mean1(accw1), .mean2(accw2));
            assign wsh0 = satf(accw0);
            assign wsh1 = satf(accw1);
            assign wsh2 = satf(accw2);
        end else begin : g_wsh_none
            assign wsh0 = {(CUR_W+1){1'b0}};
            assign wsh1 = {(CUR_W+1){1'b0}};
            assign wsh2 = {(CUR_W+1){1'b0}};
            wire unused_wsh = &{1'b0, wx_win, wx_first, wx_db, wsh0, wsh1, wsh2};   // per-axis accumulators instead
        end
    endgenerate

    // ================================================================ per axis
    genvar ax;
    generate
        for (ax = 0; ax < NAXES; ax = ax + 1) begin : g_ax
            // window of this axis: centre at grid cycle C0 + ax*STAGGER (a whole number of frames)
            localparam integer CN   = C0 + ax * STAGGER;
            localparam integer MN   = M0 + (ax * STAGGER) / TF;
            localparam integer WLN  = MN + NW - 1;
            localparam integer GPCN = (CN > G0) ? (CN - 1 - G0) / TF + 1 : 0;
            localparam [GP_W-1:0] W_FIRST = MN[GP_W-1:0];
            localparam [GP_W-1:0] W_LASTG = WLN[GP_W-1:0];
            localparam [GP_W-1:0] GP_CEN  = GPCN[GP_W-1:0];

            wire                ps       = period_start[ax];
            wire                bon      = bridges_on[ax];
            wire [2:0]          mi       = miso_s[3 * ax +: 3];
            wire [ADC_BITS-1:0] a_oc_thr = oc_thr[ax * ADC_BITS +: ADC_BITS];
            wire [ADC_BITS-1:0] a_sum_thr = sum_thr[ax * ADC_BITS +: ADC_BITS];
            wire [2:0]          a_off_we = off_we[3 * ax +: 3];
            wire [ADC_BITS-1:0] a_off_wdata = off_wdata[ax * ADC_BITS +: ADC_BITS];

            // ---------------------------------------- window flags, centre check
            wire            w_in    = (gp >= W_FIRST) && (gp <= W_LASTG);
            wire            w_first = (gp == W_FIRST);
            wire            w_last  = (gp == W_LASTG);
            reg             win_open;          // window started, its last frame not yet started
            // NAXES > 1: a window frame counts only in a window that started (after a grid jump)
            wire            w_ok    = (NAXES == 1) || w_first || win_open;
            wire            trig_ok = (gc == GC_CEN) && (gp == GP_CEN);
            wire            miss_now = (trig[ax] & ~trig_ok) | ((ps | g_jump) & win_open);
            reg             r_trig_miss;
            reg [MISS_W-1:0] r_miss_cnt;
            wire [MISS_W:0] miss_p1 = {1'b0, r_miss_cnt} + {{MISS_W{1'b0}}, 1'b1};
            reg             f_win, f_first, f_last;   // this frame's place in the window
            always @(posedge clk) begin
                if (rst) begin
                    win_open    <= 1'b0;
                    f_win       <= 1'b0;
                    f_first     <= 1'b0;
                    f_last      <= 1'b0;
                    r_trig_miss <= 1'b0;
                    r_miss_cnt  <= {MISS_W{1'b0}};
                end else begin
                    r_trig_miss <= miss_now;
                    if (miss_now && !miss_p1[MISS_W])
                        r_miss_cnt <= miss_p1[MISS_W-1:0];
                    if (ps || g_jump) win_open <= 1'b0;
                    if (accept) begin
                        f_win   <= w_in & w_ok;
                        f_first <= w_first;
                        f_last  <= w_last & w_ok;
                        if (w_first) win_open <= 1'b1;
                        if (w_last)  win_open <= 1'b0;
                    end
                end
            end

            // ---------------------------------------- capture
            // The bit leaving sh_i at a capture is the previous frame's bit at the same place:
            // comparing them finds a frame that differs from the previous one without storing it.
            reg [FRAME_BITS-1:0] sh0, sh1, sh2;
            reg [CODE_MSB:0] shc;              // code (+ trailing) bits of channel cal_ch (calibration)
            reg [1:0]        cal_ch;           // channel being calibrated
            reg [2:0]        fchg;             // frame differs from the previous one (per channel)
            reg [2:0]        ctr;              // a code bit differed from the code bit before it (per channel)
            always @(posedge clk) begin
                if (rst) begin
                    sh0  <= {FRAME_BITS{1'b0}};
                    sh1  <= {FRAME_BITS{1'b0}};
                    sh2  <= {FRAME_BITS{1'b0}};
                    shc  <= {(CODE_MSB+1){1'b0}};
                    fchg <= 3'b000;
                    ctr  <= 3'b000;
                end else begin
                    if (accept)
                        fchg <= 3'b000;
                    else if (cap)
                        fchg <= fchg | ({sh2[FRAME_BITS-1], sh1[FRAME_BITS-1], sh0[FRAME_BITS-1]} ^ mi);
                    // a code at a rail (0 or full scale) has all its bits equal: no code bit after the
                    // MSB differs from the one captured before it (sh_i[0])
                    if (accept)
                        ctr <= 3'b000;
                    else if (cap && cpipe[PIPE_N-1])
                        ctr <= ctr | ({sh2[0], sh1[0], sh0[0]} ^ mi);
                    if (cap) begin
                        sh0 <= {sh0[FRAME_BITS-2:0], mi[0]};
                        sh1 <= {sh1[FRAME_BITS-2:0], mi[1]};
                        sh2 <= {sh2[FRAME_BITS-2:0], mi[2]};
                        shc <= {shc[CODE_MSB-1:0], cal_ch[1] ? mi[2] : cal_ch[0] ? mi[1] : mi[0]};
                    end
                end
            end

            // ---------------------------------------- stage A: codes, differences, rails
            wire [ADC_BITS-1:0] fcode0 = sh0[CODE_MSB -: ADC_BITS];
            wire [ADC_BITS-1:0] fcode1 = sh1[CODE_MSB -: ADC_BITS];
            wire [ADC_BITS-1:0] fcode2 = sh2[CODE_MSB -: ADC_BITS];
            wire lead_bad = (|sh0[FRAME_BITS-1 -: LEAD_ZEROS]) | (|sh1[FRAME_BITS-1 -: LEAD_ZEROS])
                          | (|sh2[FRAME_BITS-1 -: LEAD_ZEROS]);
            wire rail = ~&ctr;                 // some channel's code at a rail
            reg [ADC_BITS-1:0]   r_code0, r_code1, r_code2;
            reg [ADC_BITS-1:0]   r_offset0, r_offset1, r_offset2;
            reg [D_W-1:0]        diff0, diff1, diff2;   // code - offset, exact (-4095..4095), two's complement
            reg                  lead_bad_a, rail_a;
            always @(posedge clk) begin
                if (rst) begin
                    r_code0    <= {ADC_BITS{1'b0}};
                    r_code1    <= {ADC_BITS{1'b0}};
                    r_code2    <= {ADC_BITS{1'b0}};
                    diff0      <= {D_W{1'b0}};
                    diff1      <= {D_W{1'b0}};
                    diff2      <= {D_W{1'b0}};
                    lead_bad_a <= 1'b0;
                    rail_a     <= 1'b0;
                end else if (capdone) begin
                    r_code0    <= fcode0;
                    r_code1    <= fcode1;
                    r_code2    <= fcode2;
                    diff0      <= {1'b0, fcode0} - {1'b0, r_offset0};
                    diff1      <= {1'b0, fcode1} - {1'b0, r_offset1};
                    diff2      <= {1'b0, fcode2} - {1'b0, r_offset2};
                    lead_bad_a <= lead_bad;
                    rail_a     <= rail;
                end
            end

            // ---------------------------------------- calibration
            // One channel after the other (cal_ch = 0, 1, 2), 2**CAL_LOG2 counted frames each,
            // on one accumulator preset to 2**(CAL_LOG2-1): its top ADC_BITS bits are then the
            // round-half-up mean (sum + 2**(CAL_LOG2-1)) >> CAL_LOG2 (cannot overflow:
            // acc <= (2**ADC_BITS-1) * 2**CAL_LOG2 + 2**(CAL_LOG2-1) < 2**ACC_W).
            localparam [ACC_W-1:0] ACC_HALF = {{ADC_BITS{1'b0}}, 1'b1, {(CAL_LOG2-1){1'b0}}};
            reg [ACC_W-1:0]      acc;
            reg [CAL_LOG2-1:0]   cal_cnt;
            reg                  cal_last;     // stage A added the channel's last sample
            reg                  frame_cal;    // this frame counts for calibration
            reg                  r_cal_busy, r_cal_done, r_refused;
            wire [ADC_BITS-1:0]  cal_code = shc[CODE_MSB -: ADC_BITS];
            // offset write port: the calibration result, or the CPU value (refused while a
            // calibration runs or the bridges are on)
            wire                 cpu_ok = ~r_cal_busy & ~bon;
            wire [ADC_BITS-1:0]  off_d = cal_last ? acc[ACC_W-1 -: ADC_BITS] : a_off_wdata;
            wire [2:0]           cal_ld = {3{cal_last}} & {cal_ch == 2'd2, cal_ch == 2'd1, cal_ch == 2'd0};
            wire [2:0]           off_ld = cal_ld | (a_off_we & {3{cpu_ok}});
            wire                 cal_go = cal_start[ax] & ~bon;
            wire                 cal_abort = r_cal_busy & bon;
            wire                 refuse = (cal_start[ax] & bon) | ((|a_off_we) & ~cpu_ok) | cal_abort;
            always @(posedge clk) begin
                if (rst) begin
                    frame_cal  <= 1'b0;
                    r_cal_busy <= 1'b0;
                    r_cal_done <= 1'b0;
                    cal_ch     <= 2'd0;
                    cal_cnt    <= {CAL_LOG2{1'b0}};
                    cal_last   <= 1'b0;
                    acc        <= ACC_HALF;
                    r_offset0  <= OFFSET_RESET[ADC_BITS-1:0];
                    r_offset1  <= OFFSET_RESET[ADC_BITS-1:0];
                    r_offset2  <= OFFSET_RESET[ADC_BITS-1:0];
                    r_refused  <= 1'b0;
                end else begin
                    cal_last  <= 1'b0;
                    r_refused <= refuse | (r_refused & ~refused_clear[ax]);
                    if (accept) frame_cal <= r_cal_busy;
                    if (off_ld[0]) r_offset0 <= off_d;
                    if (off_ld[1]) r_offset1 <= off_d;
                    if (off_ld[2]) r_offset2 <= off_d;
                    // accumulate at stage A
                    if (capdone && frame_cal) begin
                        acc       <= acc + {{CAL_LOG2{1'b0}}, cal_code};
                        cal_cnt   <= cal_cnt + 1'b1;
                        cal_last  <= (cal_cnt == CAL_LAST);
                        frame_cal <= 1'b0;
                    end
                    // load the offset at stage B, next channel
                    if (cal_last) begin
                        acc    <= ACC_HALF;
                        cal_ch <= cal_ch + 2'd1;
                        if (cal_ch == 2'd2) begin
                            r_cal_busy <= 1'b0;
                            r_cal_done <= 1'b1;
                        end
                    end
                    // bridges on: stop (the channels already loaded were measured with them off)
                    if (cal_abort) begin
                        r_cal_busy <= 1'b0;
                        frame_cal  <= 1'b0;
                    end
                    // (re)start: clears everything, the frame in flight does not count
                    if (cal_go) begin
                        r_cal_busy <= 1'b1;
                        r_cal_done <= 1'b0;
                        cal_ch     <= 2'd0;
                        cal_cnt    <= {CAL_LOG2{1'b0}};
                        cal_last   <= 1'b0;
                        frame_cal  <= 1'b0;
                        acc        <= ACC_HALF;
                    end
                end
            end

            // ---------------------------------------- stage B: overcurrent, frame error, rails
            wire [2:0] oc_now = {oc_f(diff2, a_oc_thr), oc_f(diff1, a_oc_thr), oc_f(diff0, a_oc_thr)};
            reg  [KP_T:0]   kth;               // consecutive frames with a rail (thermometer)
            reg             r_frame_err, r_oc, r_stuck;
            reg  [2:0]      r_oc_ch;
            always @(posedge clk) begin
                if (rst) begin
                    r_frame_err <= 1'b0;
                    r_oc        <= 1'b0;
                    r_oc_ch     <= 3'b000;
                    r_stuck     <= 1'b0;
                end else begin
                    r_frame_err <= st_a & lead_bad_a;
                    r_oc        <= st_a & (|oc_now);
                    if (st_a) begin
                        r_oc_ch <= oc_now;
                        r_stuck <= rail_a && kth[KP_T];
                    end
                end
            end
            always @(posedge clk) begin              // a frame without a rail clears (reset pin)
                if (rst || (st_a && !rail_a))
                    kth <= KP_ONE;
                else if (st_a)
                    kth <= (kth << 1) | KP_ONE;
            end

            // ---------------------------------------- serial pass (adders of this axis)
            reg              p_win, p_first, p_last, p_pfirst, p_padd;
            reg [ADC_BITS-1:0] p_thr;
            reg [1:0]        s_c;              // carry of d0 + d1 + d2 (0..2)
            reg              a_c, b_c;
            reg [2:0]        q_c;              // period adder carries
            reg [SP_T:0]     sth;              // consecutive frames with |s| > thr (thermometer)
            reg [PCNT_W-1:0] pcnt;
            reg              pfresh, snap_req, r_sum_err;
            reg signed [PSW-1:0] pacc0, pacc1, pacc2;
            reg signed [PSW-1:0] r_psum0, r_psum1, r_psum2;
            reg [PCNT_W-1:0] r_pcount;
            wire [2:0] db = {diff2[jd], diff1[jd], diff0[jd]};
            wire             tb = (pj < PJ_AB) ? p_thr[pj[JT_W-1:0]] : 1'b0;
            wire [2:0]       s3 = {2'b00, db[0]} + {2'b00, db[1]} + {2'b00, db[2]} + {1'b0, s_c};
            wire             sb = s3[0];
            wire             a_b = sb ^ ~tb ^ a_c;          // s + ~thr  = s - thr - 1
            wire             b_b = sb ^ tb ^ b_c;           // s + thr
            wire             sbad = ~a_b | b_b;             // at j = SW-1: |s| > thr
            wire [2:0]       pa = p_pfirst ? 3'b000 : {pacc2[0], pacc1[0], pacc0[0]};
            wire [2:0]       pd = db & {3{p_padd}};
            wire [2:0]       pq = pa ^ pd ^ q_c;
            wire             snap_now = (ps | snap_req) & ~pbusy;
            always @(posedge clk) begin
                if (rst) begin
                    p_win     <= 1'b0;
                    p_first   <= 1'b0;
                    p_last    <= 1'b0;
                    p_pfirst  <= 1'b0;
                    p_padd    <= 1'b0;
                    p_thr     <= {ADC_BITS{1'b0}};
                    pfresh    <= 1'b1;
                    snap_req  <= 1'b0;
                    pacc0     <= {PSW{1'b0}};
                    pacc1     <= {PSW{1'b0}};
                    pacc2     <= {PSW{1'b0}};
                    r_psum0   <= {PSW{1'b0}};
                    r_psum1   <= {PSW{1'b0}};
                    r_psum2   <= {PSW{1'b0}};
                    r_pcount  <= {PCNT_W{1'b0}};
                end else begin
                    // period boundary: take the sums once no pass is running
                    snap_req <= (ps | snap_req) & pbusy;
                    if (snap_now) begin
                        r_psum0  <= pacc0;
                        r_psum1  <= pacc1;
                        r_psum2  <= pacc2;
                        r_pcount <= pcnt;
                    end
                    if (st_a) begin                         // pass start (stage B)
                        p_win    <= f_win;
                        p_first  <= f_first;
                        p_last   <= f_last;
                        p_thr    <= a_sum_thr;
                        p_pfirst <= pfresh | snap_now;
                        p_padd   <= pfresh | snap_now | (pcnt != PCNT_MAX);
                        pfresh   <= 1'b0;
                    end else begin
                        if (snap_now)
                            pfresh <= 1'b1;
                        if (pbusy && pj < PJ_PSW) begin
                            pacc0 <= {pq[0], pacc0[PSW-1:1]};
                            pacc1 <= {pq[1], pacc1[PSW-1:1]};
                            pacc2 <= {pq[2], pacc2[PSW-1:1]};
                        end
                    end
                end
            end
            // frames of this period: cleared by a snapshot outside stage B (reset pin), counted at stage B
            // (restarting at 1 with the period's first frame, saturating)
            wire p_new = pfresh | snap_now;
            always @(posedge clk) begin
                if (rst || (snap_now && !st_a))
                    pcnt <= {PCNT_W{1'b0}};
                else if (st_a && (p_new || pcnt != PCNT_MAX))
                    pcnt <= (p_new ? {PCNT_W{1'b0}} : pcnt) + 1'b1;
            end
            // carries: cleared at the pass start (p_clr), stepped in the pass
            always @(posedge clk) begin
                if (p_clr) begin
                    s_c <= 2'd0;
                    a_c <= 1'b0;
                    b_c <= 1'b0;
                    q_c <= 3'b000;
                end else if (pbusy) begin
                    s_c <= s3[2:1];
                    a_c <= (sb & ~tb) | (sb & a_c) | (~tb & a_c);
                    b_c <= (sb & tb) | (sb & b_c) | (tb & b_c);
                    if (pj < PJ_PSW)
                        q_c <= (pa & pd) | (pa & q_c) | (pd & q_c);
                end
            end
            // sum check persistence at the sign bit: a good frame clears the thermometer (reset pin)
            always @(posedge clk) begin
                if (rst || (p_sce && !sbad))
                    sth <= SP_ONE;
                else if (p_sce)
                    sth <= (sth << 1) | SP_ONE;
                if (rst)
                    r_sum_err <= 1'b0;
                else if (p_sce)
                    r_sum_err <= sbad && sth[SP_T];
            end

            // ---------------------------------------- window mean
            // AVG_LOG2 = 0 takes the centre frame's difference at stage B (as the single
            // conversion did); AVG_LOG2 > 0 accumulates the window bit-serially
            // each branch gives the window's end (w_take) and its saturated means (m0..m2, bit CUR_W = saturated);
            // one set of output registers takes them
            reg                    r_valid, r_sat;
            reg signed [CUR_W-1:0] r_cur0, r_cur1, r_cur2;
            wire                   w_take;
            wire [CUR_W:0]         m0, m1, m2;
            always @(posedge clk) begin
                if (rst) begin
                    r_valid <= 1'b0;
                    r_sat   <= 1'b0;
                    r_cur0  <= {CUR_W{1'b0}};
                    r_cur1  <= {CUR_W{1'b0}};
                    r_cur2  <= {CUR_W{1'b0}};
                end else begin
                    r_valid <= w_take;
                    r_sat   <= w_take & (m0[CUR_W] | m1[CUR_W] | m2[CUR_W]);
                    if (w_take) begin
                        r_cur0 <= m0[CUR_W-1:0];
                        r_cur1 <= m1[CUR_W-1:0];
                        r_cur2 <= m2[CUR_W-1:0];
                    end
                end
            end
            if (AVG_LOG2 == 0) begin : g_k0
                assign w_take = st_a & f_last;
                assign m0 = satf(diff0);
                assign m1 = satf(diff1);
                assign m2 = satf(diff2);
                wire unused_k0 = &{1'b0, f_first, p_win, p_first, p_last};
            end else if (WSHARE != 0) begin : g_kw
                // the shared accumulator (g_wsh) holds this axis's window sum at its last frame
                assign w_take = pbusy && p_win && p_last && (pj == PJ_WEND);
                assign m0 = wsh0;
                assign m1 = wsh1;
                assign m2 = wsh2;
            end else begin : g_kn
                wire [AW-AVG_LOG2-1:0] accw0, accw1, accw2;
                adc_win_acc #(.AW(AW), .K(AVG_LOG2)) u_acc (
                    .clk(clk), .rst(rst), .p_clr(p_clr), .st_a(st_a),
                    .step_en(pbusy && p_win && pj < PJ_WEND), .first(p_first), .km1(pj == PJ_KM1), .db(db),
                    .mean0(accw0), .mean1(accw1), .mean2(accw2));
                assign m0 = satf(accw0);
                assign m1 = satf(accw1);
                assign m2 = satf(accw2);
                assign w_take = pbusy && p_win && p_last && (pj == PJ_WEND);
            end

            // ---------------------------------------- frozen ADC (per PWM period of the axis)
            reg [2:0]        chg;              // channel changed in some frame of this period
            reg              on_all;           // bridges on in every cycle of this period
            reg [FZ_T:0]     fzt;              // consecutive frozen periods (thermometer)
            reg              r_frozen;
            wire             frz_p = on_all & bon & (pcnt > 1) & ~(&chg);
            always @(posedge clk) begin
                if (rst) begin
                    chg      <= 3'b000;
                    on_all   <= 1'b0;
                    r_frozen <= 1'b0;
                end else begin
                    on_all <= ps ? bon : (on_all & bon);
                    if (ps) begin
                        chg      <= st_a ? fchg : 3'b000;   // a frame ending now is the new period's
                        r_frozen <= frz_p && fzt[FZ_T];
                    end else if (st_a) begin
                        chg <= chg | fchg;
                    end
                end
            end
            always @(posedge clk) begin              // a period not frozen clears (reset pin)
                if (rst || (ps && !frz_p))
                    fzt <= FZ_ONE;
                else if (ps)
                    fzt <= (fzt << 1) | FZ_ONE;
            end

            assign wx_win[ax]         = p_win;
            assign wx_first[ax]       = p_first;
            assign wx_db[3 * ax +: 3] = db;

            // ---------------------------------------- outputs of axis ax
            assign trig_miss[ax]                      = r_trig_miss;
            assign miss_cnt[ax * MISS_W +: MISS_W]    = r_miss_cnt;
            assign code0[ax * ADC_BITS +: ADC_BITS]   = r_code0;
            assign code1[ax * ADC_BITS +: ADC_BITS]   = r_code1;
            assign code2[ax * ADC_BITS +: ADC_BITS]   = r_code2;
            assign frame_err[ax]                      = r_frame_err;
            assign oc[ax]                             = r_oc;
            assign oc_ch[3 * ax +: 3]                 = r_oc_ch;
            assign sum_err[ax]                        = r_sum_err;
            assign stuck[ax]                          = r_stuck;
            assign frozen[ax]                         = r_frozen;
            assign valid[ax]                          = r_valid;
            assign cur0[ax * CUR_W +: CUR_W]          = r_cur0;
            assign cur1[ax * CUR_W +: CUR_W]          = r_cur1;
            assign cur2[ax * CUR_W +: CUR_W]          = r_cur2;
            assign sat[ax]                            = r_sat;
            assign psum0[ax * PSW +: PSW]             = r_psum0;
            assign psum1[ax * PSW +: PSW]             = r_psum1;
            assign psum2[ax * PSW +: PSW]             = r_psum2;
            assign pcount[ax * PCNT_W +: PCNT_W]      = r_pcount;
            assign offset0[ax * ADC_BITS +: ADC_BITS] = r_offset0;
            assign offset1[ax * ADC_BITS +: ADC_BITS] = r_offset1;
            assign offset2[ax * ADC_BITS +: ADC_BITS] = r_offset2;
            assign cal_busy[ax]                       = r_cal_busy;
            assign cal_done[ax]                       = r_cal_done;
            assign refused[ax]                        = r_refused;
        end
    endgenerate
endmodule
`default_nettype wire
