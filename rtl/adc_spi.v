// adc_spi: SPI master for the 3-channel, 12-bit phase-current ADC.
//
// Three simultaneous-sampling serial ADCs (AD7476 / ADS7886 style) share one
// SCLK and one active-low CS; each returns its frame on its own MISO line.
// A conversion is started by `trig` (one clk pulse from the PWM at the
// period centre).  Full description: docs/blocks/adc_spi.md.
//
// SPI protocol (CPOL = 1: SCLK idles high; data launched by the slave on
// CS falling (bit 0) and on SCLK falling edges 1..FRAME_BITS-1 (bits 1..);
// FRAME_BITS SCLK cycles per frame).  Frame, MSB first:
//   LEAD_ZEROS zeros | ADC_BITS code bits MSB first | trailing bits (ignored)
// Timing in clk edges after the edge E0 that accepts `trig`:
//   CS falls at E0, SCLK falling edge k (k = 1..FRAME_BITS) at E0 + 2*k*SCLK_DIV,
//   rising edge k at E0 + (2*k+1)*SCLK_DIV  (SCLK = clk / (2*SCLK_DIV)).
//   Bit k (launched at E0 + 2*k*SCLK_DIV) is latched from the synchronised
//   MISO at E0 + 2*k*SCLK_DIV + SAMPLE_DELAY: the MISO pins go through
//   sync_2ff (2 stages), so the pin itself is sampled at launch +
//   SAMPLE_DELAY - 2 clk; this must lie after the round trip
//   (clk->SCLK pin + slave t_DO + board/isolator) and before the next launch
//   plus the slave's minimum hold time.  SAMPLE_DELAY may exceed
//   2*SCLK_DIV (long isolated links): strobes are delayed in a pipeline.
//   CS rises at E0 + max((2*FRAME_BITS+2)*SCLK_DIV,
//                        2*(FRAME_BITS-1)*SCLK_DIV + SAMPLE_DELAY + 1).
//   `valid` is high in the single cycle after edge
//   E0 + VALID_LAT, VALID_LAT = 2*(FRAME_BITS-1)*SCLK_DIV + SAMPLE_DELAY + 2
//   (defaults: 67 clk = 670 ns).  CS stays high >= CS_QUIET clk.
//   `busy` (frame, CS quiet time, result pipeline) is low again after
//   max(t_CSrise + CS_QUIET - 1, E0 + VALID_LAT): a trig is accepted iff
//   busy is low in its cycle (next CS fall >= CS_QUIET clk after CS rise);
//   minimum trigger period = max(t_CSrise - E0 + CS_QUIET, VALID_LAT + 1)
//   (defaults: 73 clk).  A trig while busy is
//   ignored, pulses `trig_miss` and increments the saturating `miss_cnt`.
//
// Outputs per channel i (0..2), all updated together with `valid`:
//   code_i  raw ADC code (unsigned ADC_BITS; updated one cycle before valid)
//   cur_i   sat(code_i - offset_i, CUR_W) signed (default 13 bit: never saturates)
//   oc_ch[i] |code_i - offset_i| > oc_thr (unsaturated difference), held
// Pulses with `valid`: sat (any cur saturated), oc (any oc_ch), frame_err
// (a leading-zero bit was 1: broken/floating MISO or frame misalignment).
//
// Offsets: offset_i resets to OFFSET_RESET; off_we[i] loads off_wdata
// (CPU) unless a calibration runs (CPU writes are ignored while cal_busy).
// cal_start (pulse) starts a calibration: the channels are averaged one after
// the other (channel 0, 1, 2), each over the next 2**CAL_LOG2 conversions
// *accepted after* cal_start (resp. after the previous channel finished), so
// 3 * 2**CAL_LOG2 conversions in all.  A channel's offset is loaded with the
// round-half-up mean (sum + 2**(CAL_LOG2-1)) >> CAL_LOG2 in the valid cycle of
// its last sample; after channel 2 cal_done is set (sticky until the next
// cal_start).  cal_busy is high meanwhile; cal_start during calibration
// restarts it.  One accumulator (preset to 2**(CAL_LOG2-1), so the mean is
// its top bits) adds the code of the channel being calibrated, which a fourth
// shift register collects from that channel's MISO.  The sequencer must keep
// the bridges off (PWM outputs safe) during calibration: conversions keep
// running on `trig` and `valid` keeps pulsing (corrected with the offsets of
// the moment).
//
// Parameters: ADC_BITS, FRAME_BITS, LEAD_ZEROS (>= 1), SCLK_DIV (>= 1),
//   SAMPLE_DELAY (>= 3), CS_QUIET (>= 1), CAL_LOG2 (>= 1), CUR_W (>= 2),
//   MISS_W, OFFSET_RESET.
// Resources (Yosys synth_xilinx xc6s, defaults): ~155 LUT, ~290 FF, no DSP, no BRAM.
// Reset (synchronous, rst): cs_n = 1, sclk = 1, idle, all outputs 0,
//   offsets = OFFSET_RESET, calibration idle, cal_done = 0, miss_cnt = 0.
`default_nettype none
`include "empc_formats.vh"
module adc_spi #(
    parameter integer ADC_BITS     = `EMPC_ADC_BITS,
    parameter integer FRAME_BITS   = 16,
    parameter integer LEAD_ZEROS   = 4,
    parameter integer SCLK_DIV     = 2,
    parameter integer SAMPLE_DELAY = 5,
    parameter integer CS_QUIET     = 5,
    parameter integer CAL_LOG2     = 6,
    parameter integer CUR_W        = ADC_BITS + 1,
    parameter integer MISS_W       = 8,
    parameter integer OFFSET_RESET = `EMPC_ADC_OFFSET
) (
    input  wire                     clk,
    input  wire                     rst,
    // conversion control
    input  wire                     trig,
    output wire                     busy,
    output reg                      trig_miss,
    output reg  [MISS_W-1:0]        miss_cnt,
    // SPI pins
    output reg                      cs_n,
    output reg                      sclk,
    input  wire [2:0]               miso,       // asynchronous
    // results
    output reg                      valid,
    output reg  [ADC_BITS-1:0]      code0,
    output reg  [ADC_BITS-1:0]      code1,
    output reg  [ADC_BITS-1:0]      code2,
    output reg  signed [CUR_W-1:0]  cur0,
    output reg  signed [CUR_W-1:0]  cur1,
    output reg  signed [CUR_W-1:0]  cur2,
    output reg                      sat,
    output reg                      frame_err,
    // overcurrent
    input  wire [ADC_BITS-1:0]      oc_thr,
    output reg                      oc,
    output reg  [2:0]               oc_ch,
    // offsets
    input  wire [2:0]               off_we,
    input  wire [ADC_BITS-1:0]      off_wdata,
    output reg  [ADC_BITS-1:0]      offset0,
    output reg  [ADC_BITS-1:0]      offset1,
    output reg  [ADC_BITS-1:0]      offset2,
    input  wire                     cal_start,
    output reg                      cal_busy,
    output reg                      cal_done
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

    localparam integer HB_LAST_I    = HB_END - 1;
    localparam integer HB_LLAUNCH_I = 2 * FRAME_BITS - 2;     // last launching half-bit
    localparam integer DIV_LAST_I   = SCLK_DIV - 1;
    localparam integer Q_LAST_I     = (CS_QUIET > 1) ? CS_QUIET - 2 : 0;
    localparam [HB_W-1:0]   HB_LAST    = HB_LAST_I[HB_W-1:0];
    localparam [HB_W-1:0]   HB_LLAUNCH = HB_LLAUNCH_I[HB_W-1:0];
    localparam [DIV_W-1:0]  DIV_LAST   = DIV_LAST_I[DIV_W-1:0];
    localparam [Q_W-1:0]    Q_LAST     = Q_LAST_I[Q_W-1:0];
    localparam [CAL_LOG2-1:0] CAL_LAST = {CAL_LOG2{1'b1}};

    localparam [1:0] S_IDLE = 2'd0, S_XFER = 2'd1, S_WAIT = 2'd2, S_QUIET = 2'd3;

    // ------------------------------------------------------------ MISO sync
    wire [2:0] miso_s;
    sync_2ff #(.WIDTH(3), .STAGES(2)) u_sync_miso (
        .clk(clk), .rst(rst), .d(miso), .q(miso_s)
    );

    // -------------------------------------------------------- frame control
    reg [1:0]        st;
    reg [DIV_W-1:0]  dcnt;
    reg [HB_W-1:0]   hb;
    reg [Q_W-1:0]    qcnt;
    reg              lstb;                 // bit launched at the previous edge
    reg              llast;                // ... and it was the last bit of the frame
    reg [PIPE_N-1:0] spipe;                // lstb delayed; spipe[PIPE_N-1] = capture now
    reg [PIPE_N-1:0] lpipe;                // llast delayed: the last capture
    reg              all_cap;              // every bit of the frame captured
    reg [CODE_MSB:0] shc;                  // code (+ trailing) bits of channel cal_ch (calibration)
    reg [1:0]        cal_ch;               // channel being calibrated
    reg [FRAME_BITS-1:0] sh0, sh1, sh2;
    reg              capdone;              // last bit captured at the previous edge
    reg              st_a;                 // stage A registered (codes, differences)
    reg              frame_cal;            // this frame counts for calibration

    wire cap     = spipe[PIPE_N-1];
    wire cap_last = lpipe[PIPE_N-1];
    wire accept  = trig & ~busy;
    wire [HB_W-1:0] hb_n = hb + 1'b1;
    // saturating miss counter: the incrementer's carry out is miss_cnt == MISS_MAX
    wire [MISS_W:0] miss_p1 = {1'b0, miss_cnt} + {{MISS_W{1'b0}}, 1'b1};

    assign busy = (st != S_IDLE) | capdone | st_a;

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
            trig_miss <= 1'b0;
            miss_cnt  <= {MISS_W{1'b0}};
        end else begin
            lstb      <= 1'b0;
            llast     <= 1'b0;
            trig_miss <= trig & busy;
            if (trig & busy && !miss_p1[MISS_W])
                miss_cnt <= miss_p1[MISS_W-1:0];
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
                end else begin
                    spipe <= {spipe[PIPE_N-2:0], lstb};
                    lpipe <= {lpipe[PIPE_N-2:0], llast};
                end
            end
        end else begin : g_pipe1
            always @(posedge clk) begin
                if (rst) begin
                    spipe <= 1'b0;
                    lpipe <= 1'b0;
                end else begin
                    spipe <= lstb;
                    lpipe <= llast;
                end
            end
        end
    endgenerate

    always @(posedge clk) begin
        if (rst) begin
            all_cap <= 1'b0;
            sh0     <= {FRAME_BITS{1'b0}};
            sh1     <= {FRAME_BITS{1'b0}};
            sh2     <= {FRAME_BITS{1'b0}};
            shc     <= {(CODE_MSB+1){1'b0}};
            capdone <= 1'b0;
        end else begin
            capdone <= cap_last;
            if (accept)
                all_cap <= 1'b0;
            else if (cap_last)
                all_cap <= 1'b1;
            if (cap) begin
                sh0  <= {sh0[FRAME_BITS-2:0], miso_s[0]};
                sh1  <= {sh1[FRAME_BITS-2:0], miso_s[1]};
                sh2  <= {sh2[FRAME_BITS-2:0], miso_s[2]};
                shc  <= {shc[CODE_MSB-1:0], cal_ch[1] ? miso_s[2] : cal_ch[0] ? miso_s[1] : miso_s[0]};
            end
        end
    end

    // ----------------------------------------- stage A: codes, differences
    wire [ADC_BITS-1:0] fcode0 = sh0[CODE_MSB -: ADC_BITS];
    wire [ADC_BITS-1:0] fcode1 = sh1[CODE_MSB -: ADC_BITS];
    wire [ADC_BITS-1:0] fcode2 = sh2[CODE_MSB -: ADC_BITS];
    wire lead_bad = (|sh0[FRAME_BITS-1 -: LEAD_ZEROS]) | (|sh1[FRAME_BITS-1 -: LEAD_ZEROS])
                  | (|sh2[FRAME_BITS-1 -: LEAD_ZEROS]);

    reg [D_W-1:0]        diff0, diff1, diff2;   // code - offset, exact (-4095..4095), two's complement
    reg                  lead_bad_a;

    always @(posedge clk) begin
        if (rst) begin
            st_a       <= 1'b0;
            code0      <= {ADC_BITS{1'b0}};
            code1      <= {ADC_BITS{1'b0}};
            code2      <= {ADC_BITS{1'b0}};
            diff0      <= {D_W{1'b0}};
            diff1      <= {D_W{1'b0}};
            diff2      <= {D_W{1'b0}};
            lead_bad_a <= 1'b0;
        end else begin
            st_a <= capdone;
            if (capdone) begin
                code0      <= fcode0;
                code1      <= fcode1;
                code2      <= fcode2;
                diff0      <= {1'b0, fcode0} - {1'b0, offset0};
                diff1      <= {1'b0, fcode1} - {1'b0, offset1};
                diff2      <= {1'b0, fcode2} - {1'b0, offset2};
                lead_bad_a <= lead_bad;
            end
        end
    end

    // -------------------------------------------------------- calibration
    // One channel after the other (cal_ch = 0, 1, 2), 2**CAL_LOG2 counted conversions each,
    // on one accumulator preset to 2**(CAL_LOG2-1): its top ADC_BITS bits are then the
    // round-half-up mean (sum + 2**(CAL_LOG2-1)) >> CAL_LOG2 (cannot overflow:
    // acc <= (2**ADC_BITS-1) * 2**CAL_LOG2 + 2**(CAL_LOG2-1) < 2**ACC_W).
    localparam [ACC_W-1:0] ACC_HALF = {{ADC_BITS{1'b0}}, 1'b1, {(CAL_LOG2-1){1'b0}}};
    reg [ACC_W-1:0]      acc;
    reg [CAL_LOG2-1:0]   cal_cnt;
    reg                  cal_last;              // stage A added the channel's last sample
    wire [ADC_BITS-1:0]  cal_code = shc[CODE_MSB -: ADC_BITS];
    // offset write port: the calibration result, or the CPU value (CPU writes are ignored
    // while cal_busy, so the end result is the same as averaging all channels at once)
    wire [ADC_BITS-1:0]  off_d = cal_last ? acc[ACC_W-1 -: ADC_BITS] : off_wdata;
    wire [2:0]           cal_ld = {3{cal_last}} & {cal_ch == 2'd2, cal_ch == 2'd1, cal_ch == 2'd0};
    wire [2:0]           off_ld = cal_ld | (off_we & {3{~cal_busy}});

    always @(posedge clk) begin
        if (rst) begin
            frame_cal <= 1'b0;
            cal_busy  <= 1'b0;
            cal_done  <= 1'b0;
            cal_ch    <= 2'd0;
            cal_cnt   <= {CAL_LOG2{1'b0}};
            cal_last  <= 1'b0;
            acc       <= ACC_HALF;
            offset0   <= OFFSET_RESET[ADC_BITS-1:0];
            offset1   <= OFFSET_RESET[ADC_BITS-1:0];
            offset2   <= OFFSET_RESET[ADC_BITS-1:0];
        end else begin
            cal_last <= 1'b0;
            if (accept) frame_cal <= cal_busy;
            if (off_ld[0]) offset0 <= off_d;
            if (off_ld[1]) offset1 <= off_d;
            if (off_ld[2]) offset2 <= off_d;
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
                    cal_busy <= 1'b0;
                    cal_done <= 1'b1;
                end
            end
            // (re)start: clears everything, the frame in flight does not count
            if (cal_start) begin
                cal_busy  <= 1'b1;
                cal_done  <= 1'b0;
                cal_ch    <= 2'd0;
                cal_cnt   <= {CAL_LOG2{1'b0}};
                cal_last  <= 1'b0;
                frame_cal <= 1'b0;
                acc       <= ACC_HALF;
            end
        end
    end

    // ---------------------- stage B: saturation, overcurrent, valid pulse
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
    wire [2:0] oc_now = {oc_f(diff2, oc_thr), oc_f(diff1, oc_thr), oc_f(diff0, oc_thr)};

    // cur = sat(d, CUR_W)
    wire [2:0]       sat_now;
    wire [CUR_W-1:0] satd0, satd1, satd2;
    generate
        if (CUR_W >= D_W) begin : g_nosat
            assign sat_now = 3'b000;
            assign satd0 = {{(CUR_W-D_W){diff0[D_W-1]}}, diff0};
            assign satd1 = {{(CUR_W-D_W){diff1[D_W-1]}}, diff1};
            assign satd2 = {{(CUR_W-D_W){diff2[D_W-1]}}, diff2};
        end else begin : g_sat
            localparam [CUR_W-1:0] CMAX = {1'b0, {(CUR_W-1){1'b1}}};
            localparam [CUR_W-1:0] CMIN = {1'b1, {(CUR_W-1){1'b0}}};
            // fits iff the bits above CUR_W-1 all equal the sign
            wire [2:0] fit = {(&diff2[D_W-1:CUR_W-1]) | ~(|diff2[D_W-1:CUR_W-1]),
                              (&diff1[D_W-1:CUR_W-1]) | ~(|diff1[D_W-1:CUR_W-1]),
                              (&diff0[D_W-1:CUR_W-1]) | ~(|diff0[D_W-1:CUR_W-1])};
            assign sat_now = ~fit;
            assign satd0 = fit[0] ? diff0[CUR_W-1:0] : (diff0[D_W-1] ? CMIN : CMAX);
            assign satd1 = fit[1] ? diff1[CUR_W-1:0] : (diff1[D_W-1] ? CMIN : CMAX);
            assign satd2 = fit[2] ? diff2[CUR_W-1:0] : (diff2[D_W-1] ? CMIN : CMAX);
        end
    endgenerate

    always @(posedge clk) begin
        if (rst) begin
            valid     <= 1'b0;
            cur0      <= {CUR_W{1'b0}};
            cur1      <= {CUR_W{1'b0}};
            cur2      <= {CUR_W{1'b0}};
            sat       <= 1'b0;
            frame_err <= 1'b0;
            oc        <= 1'b0;
            oc_ch     <= 3'b000;
        end else begin
            valid     <= st_a;
            sat       <= st_a & (|sat_now);
            frame_err <= st_a & lead_bad_a;
            oc        <= st_a & (|oc_now);
            if (st_a) begin
                cur0  <= satd0;
                cur1  <= satd1;
                cur2  <= satd2;
                oc_ch <= oc_now;
            end
        end
    end
endmodule
`default_nettype wire
