//! One module per published problem.

pub mod f_a1;
pub mod f_a12;
pub mod f_a13;
pub mod f_a2;
pub mod f_a3;
pub mod f_a4;
pub mod f_a5;
pub mod f_a6;
pub mod fuller;
pub mod fuller_scenes;
pub mod r_c7x;
pub mod r_p1;
pub mod r_p2;
pub mod r_p3;
pub mod r_p4;
pub mod r_p5;
pub mod r_p6;
pub mod r_p9a;
