// adc_win_acc: adc_spi's bit-serial window accumulator for the three channels (the sum of the 2^K
// window frames' differences, LSB first, one bit per serial-pass clock).
//
// adc_spi instantiates it once per axis, or once for all axes when their windows are disjoint
// (WSHARE: the inputs are then the OR of the axes' window bits).  `first` marks the window's first
// frame: its pass adds the rounding half (bit K-1, `km1`) instead of the old sum.  A step moves the
// three accumulators right by one bit while `step_en` (the pass is in the window's bits) and not
// at a pass start (`st_a`); the carries clear at every pass start (`p_clr`).  `mean0..2` are the
// sums' bits AW-1:K (the window means, rounded by the half added at the first frame).
// Reset (synchronous, rst): accumulators 0; the carries clear with p_clr (tied to rst | pass start).
`default_nettype none
module adc_win_acc #(
    parameter integer AW = 15,                // accumulator width: difference width + K
    parameter integer K  = 2                  // 2^K window frames (K >= 1)
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          p_clr,               // clear the carries (rst or the pass start)
    input  wire          st_a,                // pass start: no accumulator step in this clock
    input  wire          step_en,             // a pass clock inside the window's bits (pbusy, win, pj < AW)
    input  wire          first,               // this pass is the window's first frame
    input  wire          km1,                 // the pass is at bit K-1 (the rounding half)
    input  wire [2:0]    db,                  // this pass bit of the three channels' differences
    output wire [AW-K-1:0] mean0,
    output wire [AW-K-1:0] mean1,
    output wire [AW-K-1:0] mean2
);
    reg  [AW-1:0] acc0, acc1, acc2;
    assign mean0 = acc0[AW-1:K];
    assign mean1 = acc1[AW-1:K];
    assign mean2 = acc2[AW-1:K];
    reg  [2:0] w_c;                           // adder carries
    wire [2:0] wa = first ? {3{km1}} : {acc2[0], acc1[0], acc0[0]};
    wire [2:0] wq = wa ^ db ^ w_c;
    always @(posedge clk) begin
        if (rst) begin
            acc0 <= {AW{1'b0}};
            acc1 <= {AW{1'b0}};
            acc2 <= {AW{1'b0}};
        end else if (!st_a && step_en) begin
            acc0 <= {wq[0], acc0[AW-1:1]};
            acc1 <= {wq[1], acc1[AW-1:1]};
            acc2 <= {wq[2], acc2[AW-1:1]};
        end
    end
    always @(posedge clk) begin
        if (p_clr)
            w_c <= 3'b000;
        else if (step_en)
            w_c <= (wa & db) | (wa & w_c) | (db & w_c);
    end
endmodule
`default_nettype wire
