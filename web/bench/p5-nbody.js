// SPDX-License-Identifier: MIT
// Example 2.9 of The Nature of Code ("n bodies") as a p5.js sketch, written
// the way the book writes it, for the benchmark (web/bench/run.mjs): every
// body attracts every other, and body i is updated inside the outer loop.
// ?n= sets the number of bodies (the book: 10).
const bodyCount = Number(new URLSearchParams(location.search).get('n') || 10);
const G = 1;
let movers = [];
window.benchFrames = 0;

class Mover {
  constructor(x, y, mass) {
    this.position = createVector(x, y);
    this.velocity = createVector(0, 0);
    this.acceleration = createVector(0, 0);
    this.mass = mass;
    this.radius = this.mass * 8;
  }

  applyForce(force) {
    let f = p5.Vector.div(force, this.mass);
    this.acceleration.add(f);
  }

  attract(mover) {
    let force = p5.Vector.sub(this.position, mover.position);
    let distance = force.mag();
    distance = constrain(distance, 5, 25);
    let strength = (G * this.mass * mover.mass) / (distance * distance);
    force.setMag(strength);
    return force;
  }

  update() {
    this.velocity.add(this.acceleration);
    this.position.add(this.velocity);
    this.acceleration.mult(0);
  }

  show() {
    stroke(0);
    strokeWeight(2);
    fill(127, 127);
    circle(this.position.x, this.position.y, this.radius * 2);
  }
}

function setup() {
  createCanvas(640, 240);
  randomSeed(0);
  for (let i = 0; i < bodyCount; i++) {
    movers[i] = new Mover(random(width), random(height), random(0.1, 2));
  }
}

function draw() {
  background(255);
  for (let i = 0; i < movers.length; i++) {
    for (let j = 0; j < movers.length; j++) {
      if (i !== j) {
        let force = movers[j].attract(movers[i]);
        movers[i].applyForce(force);
      }
    }
    movers[i].update();
    movers[i].show();
  }
  window.benchFrames += 1;
}
